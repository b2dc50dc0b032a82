//! The tile loop's body when the integrator shares light among 2x2 pixel groups
//! (`core/src/integrator/reuse.rs`).
use crate::render::{Tile, TileProbe};
use std::ops::Range;
use tessera_core::film::PixelAccum;
use tessera_core::integrator::{Integrator, GROUP};
use tessera_core::render::{group_of, render_group_cached, GroupCache};
use tessera_core::scene::Scene;

/// A tile's pixels when the integrator shares light among 2x2 groups: group by group, each
/// group's paths traced for every sample any of its pixels in the tile takes (pixels outside the
/// tile are traced for their neighbours and dropped), so a pixel's values do not depend on the
/// tiling.
#[allow(clippy::too_many_arguments)]
pub(crate) fn render_tile_groups<P: TileProbe>(
    scene: &Scene,
    integrator: &Integrator,
    seed: u64,
    t: &Tile,
    acc: &mut [PixelAccum],
    range: &dyn Fn(&PixelAccum, u32, u32) -> Range<u64>,
    groups: &mut GroupCache,
    probe: &mut P,
) {
    let tw = (t.x1 - t.x0) as usize;
    for gy in (t.y0 & !1..t.y1).step_by(2) {
        for gx in (t.x0 & !1..t.x1).step_by(2) {
            let (pixels, n) = group_of(scene, gx, gy);
            // Each pixel's index into `acc` and its samples, for the pixels in the tile.
            let mut mine: [Option<(usize, Range<u64>)>; GROUP] = Default::default();
            let (mut lo, mut hi) = (u64::MAX, 0);
            for (k, &(x, y)) in pixels[..n].iter().enumerate() {
                if x < t.x0 || x >= t.x1 || y < t.y0 || y >= t.y1 {
                    continue;
                }
                let i = (y - t.y0) as usize * tw + (x - t.x0) as usize;
                let r = range(&acc[i], x, y);
                if !r.is_empty() {
                    (lo, hi) = (lo.min(r.start), hi.max(r.end));
                    mine[k] = Some((i, r));
                }
            }
            if lo >= hi {
                continue;
            }
            let mut next = [lo; GROUP];
            render_group_cached(
                scene,
                integrator,
                seed,
                &pixels[..n],
                lo..hi,
                groups,
                probe,
                |k, c| {
                    let index = next[k];
                    next[k] += 1;
                    if let Some((i, r)) = &mine[k] {
                        if r.contains(&index) {
                            acc[*i].add(c);
                        }
                    }
                },
            );
        }
    }
}

//! The tile loop's body when the integrator shares light among groups of pixels (4x2,
//! `core/src/integrator/reuse.rs`).
use crate::tile::Tile;
use crate::tile_sums::TileSums;
use std::cell::Cell;
use std::ops::Range;
use tessera_core::film::PixelAccum;
use tessera_core::integrator::{Probe, GROUP, GROUP_H, GROUP_W};
use tessera_core::render::{GroupCache, RenderJob};

/// Which of a group's pixels take part in each of the group's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Sharing {
    /// Every pixel of the group, at every sample index any of its pixels in the tile takes
    /// (pixels outside the tile, or past their own range, are traced for their neighbours and
    /// dropped): a pixel's values depend only on its group and sample indices, not on the
    /// tiling, a crop or where an interrupted render stopped.
    Whole,
    /// Only the pixels whose own range holds the index (adaptive passes, where the pixels of a
    /// group take different numbers of samples): no path is traced only to be dropped. The
    /// values then depend on the pass's ranges, which are a function of the accumulators and
    /// the pass's targets; the tiles must hold whole groups (edges and corners at multiples of
    /// the group's dimensions).
    OwnRanges,
}

impl Sharing {
    /// The sharing for a render loop with path reuse on or off and per-pixel targets (adaptive
    /// passes) or not, and the tile edge it needs: `OwnRanges` rounds `tile_size` up to a
    /// multiple of both group dimensions, so that tiles (from the image's corner, as adaptive
    /// renders' are) hold whole groups. Tiles change no bit.
    pub(crate) fn choose(reuse: bool, targets: bool, tile_size: u32) -> (Sharing, u32) {
        if reuse && targets {
            let edge = lcm(GROUP_W, GROUP_H);
            (Sharing::OwnRanges, tile_size.max(1).next_multiple_of(edge))
        } else {
            (Sharing::Whole, tile_size)
        }
    }
}

/// The least common multiple of two positive numbers.
fn lcm(a: u32, b: u32) -> u32 {
    let (mut x, mut y) = (a, b);
    while y != 0 {
        (x, y) = (y, x % y);
    }
    a / x * b
}

/// A tile's pixels when the integrator shares light among groups, group by group (see
/// [`Sharing`] for which pixels take part in each sample). With `rays` (the cell `probe` counts
/// rays into), each pixel's ray count grows by its group's rays at each index it takes.
pub(crate) fn render_tile_groups<P: Probe>(
    job: &RenderJob,
    t: &Tile,
    acc: &mut TileSums,
    range: &dyn Fn(&PixelAccum, u32, u32) -> Range<u64>,
    sharing: Sharing,
    groups: &mut GroupCache,
    (probe, rays): (&mut P, Option<&Cell<u64>>),
) {
    let tw = (t.x1 - t.x0) as usize;
    for gy in (t.y0 - t.y0 % GROUP_H..t.y1).step_by(GROUP_H as usize) {
        for gx in (t.x0 - t.x0 % GROUP_W..t.x1).step_by(GROUP_W as usize) {
            let (pixels, n) = job.group_of(gx, gy);
            // Each pixel's index into `acc` and its samples, for the pixels in the tile.
            let mut mine: [Option<(usize, Range<u64>)>; GROUP] = Default::default();
            let (mut lo, mut hi) = (u64::MAX, 0);
            for (k, &(x, y)) in pixels[..n].iter().enumerate() {
                if x < t.x0 || x >= t.x1 || y < t.y0 || y >= t.y1 {
                    continue;
                }
                let i = (y - t.y0) as usize * tw + (x - t.x0) as usize;
                let r = range(&acc.pixels[i], x, y);
                if !r.is_empty() {
                    (lo, hi) = (lo.min(r.start), hi.max(r.end));
                }
                mine[k] = Some((i, r));
            }
            if lo >= hi {
                continue;
            }
            let samples: [Range<u64>; GROUP] = std::array::from_fn(|k| match (&mine[k], sharing) {
                (Some((_, r)), Sharing::OwnRanges) => r.clone(),
                _ => lo..hi,
            });
            // The group's rays at a sample index are all cast before the index's first value
            // arrives; every pixel taking the index is charged all of them (the cost of a sample
            // of its group, the same whichever pixels of the group the tile holds).
            let (mut at, mut cost) = (None, 0);
            job.group(
                &pixels[..n],
                &samples[..n],
                groups,
                probe,
                |k, index, c, o| {
                    if let Some(rays) = rays.filter(|_| at != Some(index)) {
                        (at, cost) = (Some(index), rays.take());
                    }
                    if let Some((i, r)) = &mine[k] {
                        if r.contains(&index) {
                            acc.add(*i, c, o);
                            acc.pixels[*i].rays += cost;
                        }
                    }
                },
            );
        }
    }
}

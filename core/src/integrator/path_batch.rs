//! The path tracer over a batch of paths stepped together: every path's ray is cast, then
//! every path takes the light its ray met, then every path scatters, and so on until all have
//! ended.
//!
//! One path at a time, each step waits on its own loads: an escaped ray's environment texels
//! are a miss in the map's tables, and the lookup cannot start before the traversal that found
//! nothing. Stepped together, the batch locates every escaped ray on the map and asks the cache
//! for its texels while the other paths' rays are still being cast, so that the misses overlap.
//! Each path keeps its own sampler and state, and its steps run in the same order as
//! [`PathIntegrator::li_probed`]'s, so each value is the one that function gives; only the
//! order of a probe's events across paths differs, which is why the render loop batches only
//! for probes that do not need it ([`Probe::IN_ORDER`]). The stage structure is also where
//! shading over several paths at once would go.
use super::path::{alive, PathIntegrator, Strategy, BSDF, EMITTER, HALF, MIS};
use super::path_state::PathState;
use super::probe::{PathEnd, Probe};
use crate::emitter::{Emitter, EnvMap};
use crate::geometry::Interaction;
use crate::light::EscapeHint;
use crate::math::{Norm, Ray};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

/// The most paths [`PathIntegrator::li_batch`] steps together.
pub const PATH_BATCH: usize = 8;

impl PathIntegrator {
    /// The radiance along each of `rays` (at most [`PATH_BATCH`]), the path from `rays[k]`
    /// drawing from `samplers[k]`, into `out[k]`: the values [`PathIntegrator::li_probed`]
    /// gives one ray at a time, the paths stepped together. `probe` sees the paths' events
    /// interleaved.
    pub fn li_batch<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        rays: &[Ray],
        samplers: &mut [S],
        probe: &mut P,
        out: &mut [Color],
    ) {
        match self.strategy {
            Strategy::Bsdf => self.batch::<BSDF, S, P>(scene, rays, samplers, probe, out),
            Strategy::Emitter => self.batch::<EMITTER, S, P>(scene, rays, samplers, probe, out),
            Strategy::Half => self.batch::<HALF, S, P>(scene, rays, samplers, probe, out),
            Strategy::Mis => self.batch::<MIS, S, P>(scene, rays, samplers, probe, out),
        }
    }

    /// [`PathIntegrator::li_batch`] for the strategy numbered `ST`.
    #[inline(always)]
    fn batch<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        rays: &[Ray],
        samplers: &mut [S],
        probe: &mut P,
        out: &mut [Color],
    ) {
        let n = rays
            .len()
            .min(samplers.len())
            .min(out.len())
            .min(PATH_BATCH);
        out[..n].fill(Color::ZERO);
        if n == 0 {
            return;
        }
        if self.max_depth == Some(0) {
            (0..n).for_each(|_| probe.end(PathEnd::MaxDepth));
            return;
        }
        let map = first_map(scene);
        let mut paths: [PathState; PATH_BATCH] =
            core::array::from_fn(|k| PathState::start(rays[k.min(n - 1)]));
        let mut live = [false; PATH_BATCH];
        live[..n].fill(true);
        let mut hits: [Option<Interaction>; PATH_BATCH] = [None; PATH_BATCH];
        let mut hints: [Option<EscapeHint>; PATH_BATCH] = [None; PATH_BATCH];
        loop {
            // Every ray cast; the texels of those that escaped asked for.
            for k in (0..n).filter(|&k| live[k]) {
                hits[k] = probe.intersect(scene, &paths[k].ray);
                hints[k] = match (&hits[k], map) {
                    (None, Some((env, m))) => m.locate(paths[k].ray.d.unit()).map(|at| {
                        m.prefetch(&at);
                        EscapeHint { env, at }
                    }),
                    _ => None,
                };
            }
            for k in 0..n {
                if !live[k] {
                    continue;
                }
                let (path, hit, o) = (&paths[k], hits[k].as_ref(), &mut out[k]);
                live[k] = self.arrive_at::<ST, P>(scene, path, hit, hints[k].as_ref(), o, probe);
            }
            let mut any = false;
            for k in 0..n {
                let Some(si) = hits[k].as_ref().filter(|_| live[k]) else {
                    continue;
                };
                let (path, sampler) = (&mut paths[k], &mut samplers[k]);
                live[k] = self.scatter::<ST, S, P>(scene, si, path, &mut out[k], sampler, probe)
                    && self.roulette(path, sampler, probe, |t| t)
                    && alive(path, probe);
                any |= live[k];
            }
            if !any {
                return;
            }
        }
    }
}

/// The scene's first environment map among its environments, with its emitter index: the one
/// escaped rays are located on ahead.
pub(super) fn first_map(scene: &Scene) -> Option<(u32, &EnvMap)> {
    scene
        .environments
        .iter()
        .find_map(|&i| match &scene.emitters[i as usize] {
            Emitter::EnvMap(m) => Some((i, m)),
            _ => None,
        })
}

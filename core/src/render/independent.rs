//! A pixel's samples with the independent sampler: camera rays made a batch at a time, then
//! their paths, one after another or stepped together.
//!
//! Each sample's camera ray is a chain of divisions and square roots, each waiting on the one
//! before; made one after another ahead of the paths, the chains of a batch overlap. Where the
//! probe allows it and the scene gains from it
//! ([`Integrator::batched_path`](crate::integrator::Integrator::batched_path)), the batch's paths
//! are then stepped together ([`PathIntegrator::li_batch`](crate::integrator::PathIntegrator::li_batch)).
//! Each sample keeps its own sampler, drawn in the same order, so no value moves.
use super::{CameraDraw, CameraSample, RenderJob};
use crate::integrator::{Probe, PATH_BATCH};
use crate::sampling::IndependentSampler;
use crate::Color;
use core::ops::Range;
use glam::Vec2;

/// How many samples of a pixel have their camera rays made together.
const CAMERA_BATCH: usize = PATH_BATCH;

impl RenderJob<'_> {
    /// [`RenderJob::pixel_alone`] for a scene whose sampler is the independent one.
    #[inline]
    pub(super) fn pixel_independent<P: Probe>(
        &self,
        x: u32,
        y: u32,
        samples: Range<u64>,
        probe: &mut P,
        mut add: impl FnMut(Color, Vec2, &CameraSample),
    ) {
        let together = match P::IN_ORDER {
            true => None,
            false => self.integrator.batched_path(self.scene),
        };
        let mut run = IndependentSampler::pixel_run(self.seed, x, y, samples);
        while let Some(first) = run.next() {
            // Past the pixel's last sample, copies of the first fill the batch, unused.
            let mut n = 1;
            let mut samplers: [IndependentSampler; CAMERA_BATCH] =
                core::array::from_fn(|k| match k {
                    0 => first.clone(),
                    _ => run
                        .next()
                        .inspect(|_| n += 1)
                        .unwrap_or_else(|| first.clone()),
                });
            let mut draws: [CameraDraw; CAMERA_BATCH] =
                [self.camera_draw(x, y, &mut samplers[0]); CAMERA_BATCH];
            for k in 1..n {
                draws[k] = self.camera_draw(x, y, &mut samplers[k]);
            }
            let Some(path) = &together else {
                for (d, sampler) in draws[..n].iter().zip(&mut samplers) {
                    let (c, o, cam) = self.finish(d, sampler, probe);
                    add(c, o, &cam);
                }
                continue;
            };
            draws[..n]
                .iter()
                .for_each(|d| probe.camera(d.pos, &d.cam.ray));
            let rays = draws.map(|d| d.cam.ray);
            let mut out = [Color::ZERO; CAMERA_BATCH];
            let paths = &mut samplers[..n];
            path.li_batch(self.scene, &rays[..n], paths, probe, &mut out[..n]);
            for (d, c) in draws[..n].iter().zip(out) {
                add(d.cam.weigh(c), d.offset, &d.cam);
            }
        }
    }
}

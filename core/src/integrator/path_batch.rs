//! The path integrator over a batch of camera rays already cast: the first vertex of every
//! path in turn, then each path's remaining bounces.
//!
//! The batch's rays are samples of one pixel, so their first vertices are alike (one shape, one
//! BSDF, the same lights): done one after another, the same code and data serve all of them.
//! Each path keeps its own sampler and its own sum, so every value is the one a path followed
//! alone gives, bit for bit.
use super::path::PathIntegrator;
use super::path_state::PathState;
use super::probe::{PathEnd, Probe};
use super::strategy::{Strategy, BSDF, EMITTER, HALF, MIS};
use crate::camera_draw::CAMERA_BATCH;
use crate::geometry::Interaction;
use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

impl PathIntegrator {
    /// For each lane `k` with a sampler, the value of the path from camera ray `rays[k]`
    /// whose hit is `hits[k]` ([`PathIntegrator::li_from_camera_hit`]'s), added to `out[k]`;
    /// lanes without a sampler are left alone. At most [`CAMERA_BATCH`] lanes.
    #[inline]
    pub(crate) fn li_from_camera_hits<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        rays: &[Ray],
        hits: &[Option<Interaction>],
        samplers: &mut [Option<S>],
        out: &mut [Color],
        probe: &mut P,
    ) {
        match self.strategy {
            Strategy::Bsdf => self.batch::<BSDF, S, P>(scene, rays, hits, samplers, out, probe),
            Strategy::Emitter => {
                self.batch::<EMITTER, S, P>(scene, rays, hits, samplers, out, probe)
            }
            Strategy::Half => self.batch::<HALF, S, P>(scene, rays, hits, samplers, out, probe),
            Strategy::Mis => self.batch::<MIS, S, P>(scene, rays, hits, samplers, out, probe),
        }
    }

    /// [`PathIntegrator::li_from_camera_hits`] for the strategy numbered `ST`.
    #[inline(always)]
    fn batch<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        rays: &[Ray],
        hits: &[Option<Interaction>],
        samplers: &mut [Option<S>],
        out: &mut [Color],
        probe: &mut P,
    ) {
        let n = rays.len().min(CAMERA_BATCH);
        let whole = |t| t;
        let mut paths: [Option<PathState>; CAMERA_BATCH] = [None; CAMERA_BATCH];
        for k in 0..n {
            let Some(sampler) = samplers[k].as_mut() else {
                continue;
            };
            if self.max_depth == Some(0) {
                probe.end(PathEnd::MaxDepth);
                continue;
            }
            let mut path = PathState::start(rays[k]);
            let result = &mut out[k];
            let Some(si) = self.arrive_at::<ST, P>(scene, &path, hits[k].as_ref(), result, probe)
            else {
                continue;
            };
            if self.leave::<ST, S, P>(scene, si, &mut path, result, sampler, probe, whole) {
                paths[k] = Some(path);
            }
        }
        for k in 0..n {
            if let (Some(path), Some(sampler)) = (paths[k].as_mut(), samplers[k].as_mut()) {
                self.follow::<ST, S, P, _>(scene, path, &mut out[k], sampler, probe, whole);
            }
        }
    }
}

//! Nori's `whitted` integrator (the course's "Whitted-style" ray tracer with area lights).
//!
//! At a surface whose BSDF has a smooth (non-delta) part, the light arriving directly from
//! emitters is estimated by one emitter sample (no BSDF sampling, no indirect light). At a
//! surface whose BSDF is only delta components (a mirror, smooth glass) the path goes on along
//! one sampled specular direction with probability 0.95, its value divided by 0.95, else ends;
//! so each sample is an unbiased estimate of the Whitted recursion, which ends with probability
//! one. Light of the emitters a ray meets counts at every vertex (the camera's included), as
//! the recursion adds `Le` at each hit.
use super::probe::{PathEnd, Probe, RayKind};
use super::unweighted_hit::cast_unweighted;
use crate::geometry::ShadingPoint;
use crate::light::sample_light;
use crate::math::Ray;
use crate::sampling::{Sampler, Stage};
use crate::scene::Scene;
use crate::Color;

/// Probability of following a specular bounce.
pub(crate) const CONTINUE: f32 = 0.95;

/// Bounces after which a path is cut: reached with probability `0.95^1000`, about `5e-23`, so
/// the cut changes no result that could be measured; it bounds the work of a pathological
/// sample.
const MAX_BOUNCES: u32 = 1000;

/// Direct light at smooth surfaces, specular chains followed with probability 0.95.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WhittedIntegrator;

impl WhittedIntegrator {
    /// One sample's radiance along `ray`.
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        mut ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let mut result = Color::ZERO;
        let mut throughput = Color::ONE;
        let mut kind = RayKind::Camera;
        for depth in 0..MAX_BOUNCES {
            let hit = cast_unweighted(scene, &ray, kind, throughput, true, &mut result, probe);
            let Some(si) = hit else {
                probe.end(PathEnd::Escaped);
                return result;
            };
            let bsdf_index = scene.shapes[si.shape as usize].bsdf;
            let bsdf = &scene.bsdfs[bsdf_index as usize];
            let traits = scene.bsdf_traits(bsdf_index);
            let g = scene.partials(bsdf_index, &si, &ray);
            let memo = scene.lookup_memo(bsdf_index);
            let at = ShadingPoint {
                uv: si.uv,
                partials: g.as_ref(),
                memo: memo.as_ref(),
            };
            let wi = si.frame.to_local(si.wi);
            if traits.has_smooth {
                if scene.features.has_emitters {
                    sampler.start_stage(depth, Stage::Light);
                    let ls = sample_light(scene, &si, bsdf, &at, wi, sampler, false, None, probe);
                    if let Some(ls) = ls {
                        result += throughput * ls.value;
                        probe.light(&ls, 1.0, throughput * ls.value);
                    }
                }
                probe.end(PathEnd::MaxDepth);
                return result;
            }
            sampler.start_stage(depth, Stage::Roulette);
            let survived = sampler.next_1d() < CONTINUE;
            probe.roulette(CONTINUE, survived, throughput);
            if !survived {
                probe.end(PathEnd::Roulette);
                return result;
            }
            sampler.start_stage(depth, Stage::Bsdf);
            let (u1, u2) = traits.draw_sample_inputs(sampler);
            let Some(bs) = bsdf.sample(wi, u1, u2, at) else {
                probe.bsdf_sample(None, glam::Vec3::ZERO, throughput);
                probe.end(PathEnd::BsdfSampleFailed);
                return result;
            };
            throughput *= bs.weight / CONTINUE;
            let d = si.frame.to_world(bs.wo);
            probe.bsdf_sample(Some(&bs), d, throughput);
            ray = si.spawn_ray(d);
            kind = RayKind::Continuation;
        }
        probe.end(PathEnd::MaxDepth);
        result
    }
}

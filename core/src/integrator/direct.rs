//! Direct illumination: light that reaches the camera after at most one bounce.
//!
//! Scene parameters: `<integrator type="direct">` (Mitsuba 3): `shading_samples` (integer,
//! default 1, sets both counts), `emitter_samples` and `bsdf_samples` (integers, default
//! `shading_samples`), combined by the power heuristic with the sample counts folded into the
//! densities; `hide_emitters` (boolean, default false). The Wakame assignment's
//! `direct_ems` (emitter sampling only: 1, 0), `direct_mats` (BSDF sampling only: 0, 1) and
//! `direct_mis` (1, 1, balance heuristic) are the same integrator with fixed settings. With a
//! count of zero, the other strategy gets weight one; a strategy that cannot produce a sample
//! (a delta light for BSDF sampling, a delta BSDF for emitter sampling) leaves it to the other.
use super::mis::Heuristic;
use super::probe::{NoProbe, PathEnd, Probe, RayKind};
use super::unweighted_hit::cast_unweighted;
use crate::geometry::ShadingPoint;
use crate::light::{emission_along, sample_light, VertexSelection};
use crate::math::Ray;
use crate::sampling::{Sampler, Stage};
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

/// Direct lighting with a number of samples per strategy.
#[derive(Clone, Copy, Debug)]
pub struct DirectIntegrator {
    /// Emitter samples per camera ray.
    pub emitter_samples: u32,
    /// BSDF samples per camera ray.
    pub bsdf_samples: u32,
    /// How the strategies are weighed.
    pub heuristic: Heuristic,
    /// Whether emitters seen directly by the camera are hidden.
    pub hide_emitters: bool,
}

impl DirectIntegrator {
    /// Radiance along `ray` from emitters seen directly and light reflected once.
    #[inline]
    pub fn li<S: Sampler>(&self, scene: &Scene, ray: Ray, sampler: &mut S) -> Color {
        self.li_probed(scene, ray, sampler, &mut NoProbe)
    }

    /// [`DirectIntegrator::li`], telling `probe` about the work done. Skipped without changing
    /// the value: emitter sampling without emitters or on an all-delta BSDF (its `eval` is
    /// zero); the BSDF density when no BSDF samples are taken (the weight is then 1); BSDF
    /// sampling when no emitter can be hit by a ray.
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let mut result = Color::ZERO;
        let hit = cast_unweighted(
            scene,
            &ray,
            RayKind::Camera,
            Color::ONE,
            !self.hide_emitters,
            &mut result,
            probe,
        );
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
        let (ne, nb) = (self.emitter_samples as f32, self.bsdf_samples as f32);
        let nee = scene.features.has_emitters && traits.has_smooth;
        let sel = if nee && self.emitter_samples > 0 {
            VertexSelection::new(
                scene.light_bounds(),
                scene.lights().lanes(),
                &si,
                bsdf,
                &at,
                wi,
            )
        } else {
            None
        };
        if nee {
            let want_pdf = self.bsdf_samples > 0;
            for i in 0..self.emitter_samples {
                // Emitter sample i reads the emitter dimensions of bounce i of the layout.
                sampler.start_stage(i, Stage::Light);
                if let Some(ls) = sample_light(
                    scene,
                    &si,
                    bsdf,
                    &at,
                    wi,
                    sampler,
                    want_pdf,
                    sel.as_ref(),
                    probe,
                ) {
                    let w = if ls.delta || self.bsdf_samples == 0 {
                        1.0
                    } else {
                        probe.mis_weight();
                        self.heuristic.weight(ne * ls.light_pdf, nb * ls.bsdf_pdf)
                    };
                    let c = ls.value * (w / ne);
                    result += c;
                    probe.light(&ls, w, c);
                }
            }
        }
        if !scene.features.has_hittable_emitters {
            probe.end(PathEnd::NothingAhead);
            return result;
        }
        for j in 0..self.bsdf_samples {
            sampler.start_stage(j, Stage::Bsdf);
            let (u1, u2) = traits.draw_sample_inputs(sampler);
            let Some(bs) = bsdf.sample(wi, u1, u2, at) else {
                probe.bsdf_sample(None, Vec3::ZERO, Color::ZERO);
                continue;
            };
            let d = si.frame.to_world(bs.wo);
            probe.bsdf_sample(Some(&bs), d, bs.weight);
            let next = probe.intersect(scene, &si.spawn_ray(d));
            probe.ray(RayKind::Continuation);
            probe.hit(scene, next.as_ref(), d);
            // Emitter sampling only runs on smooth BSDFs and cannot produce a delta direction.
            let mis = self.emitter_samples > 0 && !bs.delta && traits.has_smooth;
            emission_along(
                scene,
                si.p,
                d,
                next.as_ref(),
                mis,
                sel.as_ref(),
                probe,
                |probe, le, light_pdf| {
                    let w = if mis {
                        probe.mis_weight();
                        self.heuristic.weight(nb * bs.pdf, ne * light_pdf)
                    } else {
                        1.0
                    };
                    let c = bs.weight * le * (w / nb);
                    result += c;
                    probe.emission(le, w, c);
                },
            );
        }
        probe.end(PathEnd::MaxDepth);
        result
    }
}

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
use super::light::{emission_along, sample_light};
use super::Heuristic;
use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

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
    pub fn li<S: Sampler>(&self, scene: &Scene, ray: Ray, sampler: &mut S) -> Color {
        let mut result = Color::ZERO;
        let hit = scene.intersect(&ray);
        if !self.hide_emitters {
            emission_along(
                scene,
                ray.o,
                ray.d.normalize(),
                hit.as_ref(),
                false,
                |le, _| result += le,
            );
        }
        let Some(si) = hit else { return result };
        let bsdf = &scene.bsdfs[scene.shapes[si.shape as usize].bsdf as usize];
        let wi = si.frame.to_local(si.wi);
        let (ne, nb) = (self.emitter_samples as f32, self.bsdf_samples as f32);
        if scene.features.has_emitters && bsdf.has_smooth() {
            for _ in 0..self.emitter_samples {
                if let Some(ls) = sample_light(scene, &si, bsdf, wi, sampler) {
                    let w = if ls.delta || self.bsdf_samples == 0 {
                        1.0
                    } else {
                        self.heuristic.weight(ne * ls.light_pdf, nb * ls.bsdf_pdf)
                    };
                    result += ls.value * (w / ne);
                }
            }
        }
        if !scene.features.has_hittable_emitters {
            return result;
        }
        for _ in 0..self.bsdf_samples {
            let u1 = sampler.next_1d();
            let u2 = sampler.next_2d();
            let Some(bs) = bsdf.sample(wi, u1, u2, si.uv) else {
                continue;
            };
            let d = si.frame.to_world(bs.wo);
            let next = scene.intersect(&si.spawn_ray(d));
            // Emitter sampling only runs on smooth BSDFs and cannot produce a delta direction.
            let mis = self.emitter_samples > 0 && !bs.delta && bsdf.has_smooth();
            emission_along(scene, si.p, d, next.as_ref(), mis, |le, light_pdf| {
                let w = if mis {
                    self.heuristic.weight(nb * bs.pdf, ne * light_pdf)
                } else {
                    1.0
                };
                result += bs.weight * le * (w / nb);
            });
        }
        result
    }
}

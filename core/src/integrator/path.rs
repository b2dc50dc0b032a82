//! Unidirectional path tracer with three ways of finding light.
//!
//! Scene parameters (`<integrator type="path_mats|path_ems|path_half|path_mis|path">`): `max_depth`
//! (integer, default -1 = unbounded; 1 = only emitters seen directly, 2 = direct lighting),
//! `rr_depth` (integer, default 5: Russian roulette from that depth on, with survival probability
//! min(max throughput * eta^2, 0.95), eta the relative index crossed so far), `hide_emitters` (boolean, default false: when set, a camera ray
//! that meets an emitter or escapes to the environment contributes nothing, as in Mitsuba 3). These follow Mitsuba 3's
//! `path` integrator exactly.
//!
//! Strategies:
//! - `path_mats`: BSDF sampling only; light counts when a path hits an emitter.
//! - `path_ems`: emitter sampling for every light a vertex can see; emitters hit by BSDF-sampled
//!   rays count only where emitter sampling could not have found them (the camera ray, after a
//!   delta bounce).
//! - `path_half`: CS500's estimator: an explicit light connection at every vertex plus implicit
//!   hits, each weighted 1/2 (weight 1 where only one of them can produce the sample: delta
//!   lights, delta BSDF components).
//! - `path_mis` / `path`: the same two strategies combined by the power heuristic (Tessera's own
//!   parameter `heuristic`, string power|balance, default power).
use super::light::{emission_along, sample_light};
use super::Heuristic;
use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

/// How a path finds light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// BSDF sampling only.
    Bsdf,
    /// Emitter sampling only (implicit hits only where it could not reach).
    Emitter,
    /// Emitter and BSDF sampling, each weighted 1/2.
    Half,
    /// Emitter and BSDF sampling combined by the power heuristic.
    Mis,
}

/// A path tracer with Mitsuba 3's depth conventions.
#[derive(Clone, Copy, Debug)]
pub struct PathIntegrator {
    /// How light is found.
    pub strategy: Strategy,
    /// Longest path in segments (`None` = unbounded).
    pub max_depth: Option<u32>,
    /// Depth from which Russian roulette applies.
    pub rr_depth: u32,
    /// Whether emitters seen directly by the camera are hidden.
    pub hide_emitters: bool,
    /// How `Strategy::Mis` weighs its two strategies.
    pub heuristic: Heuristic,
}

impl Default for PathIntegrator {
    fn default() -> Self {
        PathIntegrator {
            strategy: Strategy::Mis,
            max_depth: None,
            rr_depth: 5,
            hide_emitters: false,
            heuristic: Heuristic::Power,
        }
    }
}

/// What the next vertex needs to know about how the path left the previous one.
#[derive(Clone, Copy)]
struct Prev {
    p: Vec3,
    /// BSDF density of the sampled direction.
    pdf: f32,
    /// Whether emitter sampling ran there and could have produced this direction.
    nee: bool,
}

impl PathIntegrator {
    /// Weight of light found by hitting an emitter; `light_pdf` gives the density with which
    /// emitter sampling at the previous vertex would have produced the same direction.
    #[inline]
    fn hit_weight(&self, prev: Option<Prev>, light_pdf: f32) -> f32 {
        let Some(prev) = prev else { return 1.0 };
        if !prev.nee {
            return 1.0;
        }
        match self.strategy {
            Strategy::Bsdf => 1.0,
            Strategy::Emitter => 0.0,
            Strategy::Half => 0.5,
            Strategy::Mis => self.heuristic.weight(prev.pdf, light_pdf),
        }
    }

    /// Radiance along `ray`.
    pub fn li<S: Sampler>(&self, scene: &Scene, mut ray: Ray, sampler: &mut S) -> Color {
        let max_depth = self.max_depth.unwrap_or(u32::MAX);
        if max_depth == 0 {
            return Color::ZERO;
        }
        let features = &scene.features;
        let mut result = Color::ZERO;
        let mut throughput = Color::ONE;
        // Product of the relative indices crossed: radiance scaling at refractions is undone
        // for Russian roulette, as in Mitsuba 3.
        let mut eta = 1.0f32;
        let mut depth = 0u32;
        let mut prev: Option<Prev> = None;
        loop {
            let visible = !(depth == 0 && self.hide_emitters);
            let hit = scene.intersect(&ray);
            // Mitsuba 3's hide_emitters: a camera ray that meets an emitter sees nothing at all.
            if !visible
                && hit
                    .as_ref()
                    .is_some_and(|si| scene.shapes[si.shape as usize].emitter.is_some())
            {
                break;
            }
            if visible && (hit.is_some() || features.has_environment) {
                let d = ray.d.normalize();
                let with_pdf = self.strategy == Strategy::Mis && prev.is_some_and(|p| p.nee);
                let from = prev.map_or(ray.o, |p| p.p);
                emission_along(scene, from, d, hit.as_ref(), with_pdf, |le, light_pdf| {
                    result += throughput * le * self.hit_weight(prev, light_pdf);
                });
            }
            let Some(si) = hit else { break };
            let shape = &scene.shapes[si.shape as usize];
            if depth + 1 >= max_depth {
                break;
            }
            let bsdf = &scene.bsdfs[shape.bsdf as usize];
            let wi = si.frame.to_local(si.wi);
            let nee = self.strategy != Strategy::Bsdf && features.has_emitters && bsdf.has_smooth();
            if nee {
                if let Some(ls) = sample_light(scene, &si, bsdf, wi, sampler) {
                    let w = match (ls.delta, self.strategy) {
                        (true, _) | (_, Strategy::Emitter) => 1.0,
                        (_, Strategy::Half) => 0.5,
                        _ => self.heuristic.weight(ls.light_pdf, ls.bsdf_pdf),
                    };
                    result += throughput * ls.value * w;
                }
            }
            let u1 = sampler.next_1d();
            let u2 = sampler.next_2d();
            let Some(bs) = bsdf.sample(wi, u1, u2, si.uv) else {
                break;
            };
            throughput *= bs.weight;
            eta *= bs.eta;
            prev = Some(Prev {
                p: si.p,
                pdf: bs.pdf,
                nee: nee && !bs.delta && features.has_hittable_emitters,
            });
            ray = si.spawn_ray(si.frame.to_world(bs.wo));
            depth += 1;
            if depth >= self.rr_depth {
                let q = (throughput.max_element() * eta * eta).min(0.95);
                if !(sampler.next_1d() < q) {
                    break;
                }
                throughput /= q;
            }
            if throughput == Color::ZERO || !throughput.is_finite() {
                break;
            }
        }
        result
    }
}

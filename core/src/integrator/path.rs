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
use super::mis::Heuristic;
use super::path_state::{PathState, Prefix, Prev, PREFIX, SUFFIX, WHOLE};
use super::probe::{NoProbe, PathEnd, Probe, RayKind};
use crate::geometry::Interaction;
use crate::light::{emission_along, sample_light, VertexSelection};
use crate::math::{Norm, Ray};
use crate::sampling::{Sampler, Stage};
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

const BSDF: u8 = 0;
const EMITTER: u8 = 1;
const HALF: u8 = 2;
const MIS: u8 = 3;

impl Strategy {
    /// The strategy numbered `n` (a const parameter of the path loop).
    #[inline(always)]
    const fn of(n: u8) -> Strategy {
        match n {
            BSDF => Strategy::Bsdf,
            EMITTER => Strategy::Emitter,
            HALF => Strategy::Half,
            _ => Strategy::Mis,
        }
    }
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
    /// Whether render loops share light among the pixels of 4x2 groups (`reuse`).
    pub reuse: bool,
}

impl Default for PathIntegrator {
    fn default() -> Self {
        PathIntegrator {
            strategy: Strategy::Mis,
            max_depth: None,
            rr_depth: 5,
            hide_emitters: false,
            heuristic: Heuristic::Power,
            reuse: false,
        }
    }
}

impl PathIntegrator {
    /// Weight of light found by hitting an emitter; `light_pdf` gives the density with which
    /// emitter sampling at the previous vertex would have produced the same direction.
    #[inline]
    fn hit_weight<P: Probe>(
        &self,
        strategy: Strategy,
        prev: Option<Prev>,
        light_pdf: f32,
        probe: &mut P,
    ) -> f32 {
        let Some(prev) = prev else { return 1.0 };
        if !prev.nee {
            return 1.0;
        }
        match strategy {
            Strategy::Bsdf => 1.0,
            Strategy::Emitter => 0.0,
            Strategy::Half => 0.5,
            Strategy::Mis => {
                probe.mis_weight();
                self.heuristic.weight(prev.pdf, light_pdf)
            }
        }
    }

    /// Radiance along `ray`.
    #[inline]
    pub fn li<S: Sampler>(&self, scene: &Scene, ray: Ray, sampler: &mut S) -> Color {
        self.li_probed(scene, ray, sampler, &mut NoProbe)
    }

    /// Radiance along `ray`, telling `probe` about the work done (the value does not depend on
    /// the probe).
    ///
    /// Work a scene does not need is skipped, each skip leaving the value unchanged:
    /// - no emitter sampling without emitters or at a vertex whose BSDF is all delta (`eval` is
    ///   zero there, so every such sample would add nothing);
    /// - no BSDF density unless the strategy weighs by it (`path_mis`);
    /// - no environment lookups without an environment;
    /// - no emission lookup where its weight is zero (`path_ems` after a vertex whose emitter
    ///   sampling could reach the light);
    /// - no last segment (BSDF sample and ray) when all it could add is light that no ray can
    ///   hit (only delta lights) or that has weight zero (`path_ems`, non-delta bounce). The
    ///   last segment is the last use of the sampler in this sample, and each sample has its
    ///   own stream, so no other value moves.
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        self.run::<WHOLE, S, P>(
            scene,
            PathState::start(ray),
            sampler,
            probe,
            &mut Prefix::default(),
        )
    }

    /// The loop in mode `MODE` (see [`WHOLE`]) for this integrator's strategy.
    #[inline(always)]
    pub(super) fn run<const MODE: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        state: PathState,
        sampler: &mut S,
        probe: &mut P,
        prefix: &mut Prefix,
    ) -> Color {
        // One loop per strategy, so that the strategy's tests fold away in each.
        match self.strategy {
            Strategy::Bsdf => self.trace::<BSDF, MODE, S, P>(scene, state, sampler, probe, prefix),
            Strategy::Emitter => {
                self.trace::<EMITTER, MODE, S, P>(scene, state, sampler, probe, prefix)
            }
            Strategy::Half => self.trace::<HALF, MODE, S, P>(scene, state, sampler, probe, prefix),
            Strategy::Mis => self.trace::<MIS, MODE, S, P>(scene, state, sampler, probe, prefix),
        }
    }

    /// Casts `ray` (segment `depth` of the path) and adds the light it finds to `result`:
    /// the hit, or `Err` when a hidden emitter ends the path.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn arrive<const ST: u8, P: Probe>(
        &self,
        scene: &Scene,
        ray: &Ray,
        depth: u32,
        prev: Option<Prev>,
        throughput: Color,
        result: &mut Color,
        probe: &mut P,
    ) -> Result<Option<Interaction>, ()> {
        let strategy = Strategy::of(ST);
        let features = &scene.features;
        let visible = !(depth == 0 && self.hide_emitters);
        let hit = probe.intersect(scene, ray);
        probe.ray(if depth == 0 {
            RayKind::Camera
        } else {
            RayKind::Continuation
        });
        probe.hit(scene, hit.as_ref(), ray.d);
        // Mitsuba 3's hide_emitters: a camera ray that meets an emitter sees nothing at all.
        if !visible
            && hit
                .as_ref()
                .is_some_and(|si| scene.shapes[si.shape as usize].emitter.is_some())
        {
            probe.end(PathEnd::HiddenEmitter);
            return Err(());
        }
        // path_ems gives light found after a vertex that sampled emitters weight zero.
        let weighted = !(strategy == Strategy::Emitter && prev.is_some_and(|p| p.nee));
        if visible && weighted && (hit.is_some() || features.has_environment) {
            let d = ray.d.unit();
            let with_pdf = strategy == Strategy::Mis && prev.is_some_and(|p| p.nee);
            let from = prev.map_or(ray.o, |p| p.p);
            emission_along(
                scene,
                from,
                d,
                hit.as_ref(),
                with_pdf,
                prev.as_ref().and_then(|p| p.sel.as_ref()),
                probe,
                |probe, le, light_pdf| {
                    let w = self.hit_weight(strategy, prev, light_pdf, probe);
                    let c = throughput * le * w;
                    *result += c;
                    probe.emission(le, w, c);
                },
            );
        }
        Ok(hit)
    }

    /// [`PathIntegrator::li_probed`] for the strategy numbered `ST` (see [`Strategy::of`]).
    #[inline(always)]
    fn trace<const ST: u8, const MODE: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        state: PathState,
        sampler: &mut S,
        probe: &mut P,
        prefix: &mut Prefix,
    ) -> Color {
        let strategy = Strategy::of(ST);
        let max_depth = self.max_depth.unwrap_or(u32::MAX);
        if max_depth == 0 {
            probe.end(PathEnd::MaxDepth);
            return Color::ZERO;
        }
        let features = &scene.features;
        let mut result = Color::ZERO;
        let PathState {
            mut ray,
            mut throughput,
            // Product of the relative indices crossed: radiance scaling at refractions is
            // undone for Russian roulette, as in Mitsuba 3.
            mut eta,
            mut depth,
            mut prev,
            rr_scale,
            mut pending,
        } = state;
        loop {
            let resumed = if MODE == SUFFIX { pending.take() } else { None };
            let hit = match resumed {
                Some(si) => Some(si),
                None => {
                    let hit = self.arrive::<ST, P>(
                        scene,
                        &ray,
                        depth,
                        prev,
                        throughput,
                        &mut result,
                        probe,
                    );
                    match hit {
                        Ok(hit) => hit,
                        Err(()) => break,
                    }
                }
            };
            let Some(si) = hit else {
                probe.end(PathEnd::Escaped);
                break;
            };
            if MODE == PREFIX && depth == 1 {
                let state = PathState {
                    ray,
                    throughput,
                    eta,
                    depth,
                    prev,
                    rr_scale: Color::ONE,
                    pending: Some(si),
                };
                prefix.y = Some(state);
                break;
            }
            let shape = &scene.shapes[si.shape as usize];
            if depth + 1 >= max_depth {
                probe.end(PathEnd::MaxDepth);
                break;
            }
            let bsdf = &scene.bsdfs[shape.bsdf as usize];
            let traits = scene.bsdf_traits(shape.bsdf);
            let wi = si.frame.to_local(si.wi);
            let nee = strategy != Strategy::Bsdf && features.has_emitters && traits.has_smooth;
            let sel = if nee {
                VertexSelection::new(scene.light_bounds(), &si, bsdf, wi)
            } else {
                None
            };
            if nee {
                let want_pdf = strategy == Strategy::Mis;
                sampler.start_stage(depth, Stage::Light);
                if let Some(ls) =
                    sample_light(scene, &si, bsdf, wi, sampler, want_pdf, sel.as_ref(), probe)
                {
                    let w = match (ls.delta, strategy) {
                        (true, _) | (_, Strategy::Emitter) => 1.0,
                        (_, Strategy::Half) => 0.5,
                        _ => {
                            probe.mis_weight();
                            self.heuristic.weight(ls.light_pdf, ls.bsdf_pdf)
                        }
                    };
                    let c = throughput * ls.value * w;
                    result += c;
                    probe.light(&ls, w, c);
                }
            }
            // The next vertex is the last: it only adds the light its ray hits.
            let last = depth + 2 >= max_depth;
            if last && !features.has_hittable_emitters {
                probe.end(PathEnd::NothingAhead);
                break;
            }
            if MODE == PREFIX && depth == 0 && traits.has_smooth {
                prefix.x = Some((si, shape.bsdf, wi));
            }
            sampler.start_stage(depth, Stage::Bsdf);
            let (u1, u2) = traits.draw_sample_inputs(sampler);
            let Some(bs) = bsdf.sample(wi, u1, u2, si.uv) else {
                probe.bsdf_sample(None, Vec3::ZERO, throughput);
                probe.end(PathEnd::BsdfSampleFailed);
                break;
            };
            let nee_next = nee && !bs.delta && features.has_hittable_emitters;
            if last && strategy == Strategy::Emitter && nee_next {
                probe.bsdf_sample(Some(&bs), si.frame.to_world(bs.wo), throughput * bs.weight);
                probe.end(PathEnd::NothingAhead);
                break;
            }
            if MODE == PREFIX {
                prefix.delta = bs.delta;
            }
            throughput *= bs.weight;
            eta *= bs.eta;
            prev = Some(Prev {
                p: si.p,
                pdf: bs.pdf,
                nee: nee_next,
                sel,
            });
            let wo = si.frame.to_world(bs.wo);
            probe.bsdf_sample(Some(&bs), wo, throughput);
            ray = si.spawn_ray(wo);
            depth += 1;
            if depth >= self.rr_depth {
                let seen = if MODE == SUFFIX {
                    throughput * rr_scale
                } else {
                    throughput
                };
                let q = (seen.max_element() * eta * eta).min(0.95);
                // The roulette belongs to the bounce just taken.
                sampler.start_stage(depth - 1, Stage::Roulette);
                let survived = sampler.next_1d() < q;
                if survived {
                    throughput /= q;
                }
                probe.roulette(q, survived, throughput);
                if !survived {
                    probe.end(PathEnd::Roulette);
                    break;
                }
            }
            // A prefix's second vertex is a sample for its neighbours too, whatever its weight.
            let zero = throughput == Color::ZERO && !(MODE == PREFIX && depth == 1);
            if zero || !throughput.is_finite() {
                probe.end(PathEnd::ZeroThroughput);
                break;
            }
        }
        result
    }
}

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
//!
//! The loop is written as steps ([`PathIntegrator::arrive`], [`PathIntegrator::scatter`],
//! [`PathIntegrator::roulette`], [`alive`]) over a [`PathState`]: [`PathIntegrator::follow`]
//! runs them until the path ends. Path reuse (`reuse_halves.rs`) composes the same steps into
//! the two halves of its group estimator.
use super::mis::Heuristic;
use super::path_state::{alive, PathState, Prev};
use super::probe::{NoProbe, PathEnd, Probe, RayKind};
use super::strategy::{Strategy, BSDF, EMITTER, HALF, MIS};
use crate::geometry::{Interaction, ShadingPoint};
use crate::light::{emission_along, sample_light, VertexSelection};
use crate::math::{Norm, Ray};
use crate::sampling::{Sampler, Stage};
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

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
        prev: Option<&Prev>,
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
    #[inline]
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        self.li_from(scene, ray, None, sampler, probe)
    }

    /// Radiance along the camera ray `ray`, whose closest hit is `hit` (what
    /// `scene.intersect(&ray)` gives): [`PathIntegrator::li_probed`]'s value, bit for bit, for a
    /// render loop that casts its camera rays before following their paths (`escapes.rs`,
    /// `path_batch.rs`). `probe` is not told about the camera ray's cast.
    #[inline]
    pub fn li_from_camera_hit<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        hit: Option<Interaction>,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        self.li_from(scene, ray, Some(hit), sampler, probe)
    }

    /// The path from the camera ray `ray`, cast here unless `first` holds its hit.
    #[inline(always)]
    fn li_from<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        first: Option<Option<Interaction>>,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        // One loop per strategy, so that the strategy's tests fold away in each.
        match self.strategy {
            Strategy::Bsdf => self.trace::<BSDF, S, P>(scene, ray, first, sampler, probe),
            Strategy::Emitter => self.trace::<EMITTER, S, P>(scene, ray, first, sampler, probe),
            Strategy::Half => self.trace::<HALF, S, P>(scene, ray, first, sampler, probe),
            Strategy::Mis => self.trace::<MIS, S, P>(scene, ray, first, sampler, probe),
        }
    }

    /// [`PathIntegrator::li_from`] for the strategy numbered `ST` (see [`Strategy::of`]): a
    /// path from the camera ray, followed until it ends.
    #[inline(always)]
    fn trace<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        first: Option<Option<Interaction>>,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let mut result = Color::ZERO;
        if self.max_depth == Some(0) {
            probe.end(PathEnd::MaxDepth);
            return result;
        }
        let mut path = PathState::start(ray);
        let whole = |t| t;
        // A camera ray cast by the caller: its step here, the loop from the next ray on.
        if let Some(hit) = first {
            let Some(si) = self.arrive_at::<ST, P>(scene, &path, hit.as_ref(), &mut result, probe)
            else {
                return result;
            };
            if !self.leave::<ST, S, P>(scene, si, &mut path, &mut result, sampler, probe, whole) {
                return result;
            }
        }
        self.follow::<ST, S, P, _>(scene, &mut path, &mut result, sampler, probe, whole);
        result
    }

    /// The path loop from `path` (whose ray is not cast yet) until the path ends, adding the
    /// light found to `result`: at each vertex the ray reaches, the light it hits, emitter
    /// sampling, BSDF sampling of the next ray and Russian roulette. `roulette_sees` maps the
    /// throughput to the one roulette's survival probability is computed from (the identity
    /// for a whole path).
    #[inline(always)]
    pub(super) fn follow<const ST: u8, S: Sampler, P: Probe, R: Fn(Color) -> Color>(
        &self,
        scene: &Scene,
        path: &mut PathState,
        result: &mut Color,
        sampler: &mut S,
        probe: &mut P,
        roulette_sees: R,
    ) {
        // The hit is borrowed where the cast wrote it: moved, it was copied with a stall.
        loop {
            let hit = probe.intersect(scene, &path.ray);
            let Some(si) = self.arrive_at::<ST, P>(scene, path, hit.as_ref(), result, probe) else {
                break;
            };
            if !self.leave::<ST, S, P>(scene, si, path, result, sampler, probe, &roulette_sees) {
                break;
            }
        }
    }

    /// Leaves the vertex `si`: emitter sampling and the BSDF-sampled next ray, then Russian
    /// roulette; whether the path goes on.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn leave<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        si: &Interaction,
        path: &mut PathState,
        result: &mut Color,
        sampler: &mut S,
        probe: &mut P,
        roulette_sees: impl Fn(Color) -> Color,
    ) -> bool {
        self.scatter::<ST, S, P>(scene, si, path, result, sampler, probe)
            && self.roulette(path, sampler, probe, roulette_sees)
            && alive(path, probe)
    }

    /// Casts the path's ray and adds the light it hits to `result`, weighted against emitter
    /// sampling at the vertex it left: the vertex reached, or `None` when the path ends (the
    /// ray escaped, or a hidden emitter ends it).
    #[inline(always)]
    pub(super) fn arrive<const ST: u8, P: Probe>(
        &self,
        scene: &Scene,
        path: &PathState,
        result: &mut Color,
        probe: &mut P,
    ) -> Option<Interaction> {
        let hit = probe.intersect(scene, &path.ray);
        self.arrive_at::<ST, P>(scene, path, hit.as_ref(), result, probe)
            .copied()
    }

    /// [`PathIntegrator::arrive`] for the path's ray, already cast: `hit` is what it met.
    #[inline(always)]
    pub(super) fn arrive_at<'h, const ST: u8, P: Probe>(
        &self,
        scene: &Scene,
        path: &PathState,
        hit: Option<&'h Interaction>,
        result: &mut Color,
        probe: &mut P,
    ) -> Option<&'h Interaction> {
        let strategy = Strategy::of(ST);
        let features = &scene.features;
        let (ray, throughput, depth) = (&path.ray, path.throughput, path.depth);
        let prev = path.prev.as_ref();
        let visible = !(depth == 0 && self.hide_emitters);
        probe.ray(if depth == 0 {
            RayKind::Camera
        } else {
            RayKind::Continuation
        });
        probe.hit(scene, hit, ray.d);
        // Mitsuba 3's hide_emitters: a camera ray that meets an emitter sees nothing at all.
        if !visible
            && hit
                .as_ref()
                .is_some_and(|si| scene.shapes[si.shape as usize].emitter.is_some())
        {
            probe.end(PathEnd::HiddenEmitter);
            return None;
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
                hit,
                with_pdf,
                prev.and(path.sel.as_ref()),
                probe,
                |probe, le, light_pdf| {
                    let w = self.hit_weight(strategy, prev, light_pdf, probe);
                    let c = throughput * le * w;
                    *result += c;
                    probe.emission(le, w, c);
                },
            );
        }
        if hit.is_none() {
            probe.end(PathEnd::Escaped);
        }
        hit
    }

    /// At vertex `si`, which the path's ray reached: emitter sampling (adding its light to
    /// `result`), then BSDF sampling of the next ray, which `path` moves on to. False when the
    /// path ends here (depth limit, nothing left to find ahead, or no direction).
    #[inline(always)]
    pub(super) fn scatter<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        si: &Interaction,
        path: &mut PathState,
        result: &mut Color,
        sampler: &mut S,
        probe: &mut P,
    ) -> bool {
        let strategy = Strategy::of(ST);
        let features = &scene.features;
        let max_depth = self.max_depth.unwrap_or(u32::MAX);
        let depth = path.depth;
        if depth + 1 >= max_depth {
            probe.end(PathEnd::MaxDepth);
            return false;
        }
        let shape = &scene.shapes[si.shape as usize];
        let bsdf = &scene.bsdfs[shape.bsdf as usize];
        let traits = scene.bsdf_traits(shape.bsdf);
        let wi = si.frame.to_local(si.wi);
        let g = scene.partials(shape.bsdf, si, &path.ray);
        let memo = scene.lookup_memo(shape.bsdf);
        let at = ShadingPoint {
            uv: si.uv,
            partials: g.as_ref(),
            memo: memo.as_ref(),
        };
        let nee = strategy != Strategy::Bsdf && features.has_emitters && traits.has_smooth;
        // The previous vertex's selection, used by `arrive_at`, gives way to this one's.
        if nee {
            VertexSelection::set(
                &mut path.sel,
                scene.light_bounds(),
                scene.lights().lanes(),
                si,
                bsdf,
                &at,
                wi,
            );
        } else {
            path.sel = None;
        }
        if nee {
            let want_pdf = strategy == Strategy::Mis;
            sampler.start_stage(depth, Stage::Light);
            if let Some(ls) = sample_light(
                scene,
                si,
                bsdf,
                &at,
                wi,
                sampler,
                want_pdf,
                path.sel.as_ref(),
                probe,
            ) {
                let w = match (ls.delta, strategy) {
                    (true, _) | (_, Strategy::Emitter) => 1.0,
                    (_, Strategy::Half) => 0.5,
                    _ => {
                        probe.mis_weight();
                        self.heuristic.weight(ls.light_pdf, ls.bsdf_pdf)
                    }
                };
                let c = path.throughput * ls.value * w;
                *result += c;
                probe.light(&ls, w, c);
            }
        }
        // The next vertex is the last: it only adds the light its ray hits.
        let last = depth + 2 >= max_depth;
        if last && !features.has_hittable_emitters {
            probe.end(PathEnd::NothingAhead);
            return false;
        }
        sampler.start_stage(depth, Stage::Bsdf);
        let (u1, u2) = traits.draw_sample_inputs(sampler);
        // Lent, so the callee copies it field by field (`From<&ShadingPoint>`).
        #[allow(clippy::needless_borrows_for_generic_args)]
        let Some(bs) = bsdf.sample(wi, u1, u2, &at) else {
            probe.bsdf_sample(None, Vec3::ZERO, path.throughput);
            probe.end(PathEnd::BsdfSampleFailed);
            return false;
        };
        let nee_next = nee && !bs.delta && features.has_hittable_emitters;
        if last && strategy == Strategy::Emitter && nee_next {
            let weighted = path.throughput * bs.weight;
            probe.bsdf_sample(Some(&bs), si.frame.to_world(bs.wo), weighted);
            probe.end(PathEnd::NothingAhead);
            return false;
        }
        path.throughput *= bs.weight;
        path.eta *= bs.eta;
        path.prev = Some(Prev {
            p: si.p,
            pdf: bs.pdf,
            nee: nee_next,
            delta: bs.delta,
        });
        let wo = si.frame.to_world(bs.wo);
        probe.bsdf_sample(Some(&bs), wo, path.throughput);
        path.ray = si.spawn_ray(wo);
        path.depth += 1;
        true
    }

    /// Russian roulette for the bounce just taken, from `rr_depth` on: survival probability
    /// min(max of `roulette_sees(throughput)` * eta^2, 0.95), the throughput divided by it on
    /// survival. False when the path ends.
    #[inline(always)]
    pub(super) fn roulette<S: Sampler, P: Probe>(
        &self,
        path: &mut PathState,
        sampler: &mut S,
        probe: &mut P,
        roulette_sees: impl Fn(Color) -> Color,
    ) -> bool {
        if path.depth < self.rr_depth {
            return true;
        }
        let q = (roulette_sees(path.throughput).max_element() * path.eta * path.eta).min(0.95);
        // The roulette belongs to the bounce just taken.
        sampler.start_stage(path.depth - 1, Stage::Roulette);
        let survived = sampler.next_1d() < q;
        if survived {
            path.throughput /= q;
        }
        probe.roulette(q, survived, path.throughput);
        if !survived {
            probe.end(PathEnd::Roulette);
        }
        survived
    }
}

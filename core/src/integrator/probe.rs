//! Observation hooks on the integrators: a [`Probe`] is told about every ray, BSDF query,
//! emitter sample, MIS weight and Russian-roulette decision of one sample's path.
//!
//! The integrators are generic over the probe; [`NoProbe`] has only empty inlined methods, so
//! the ordinary render (`li` = `li_probed` with `NoProbe`) compiles to the same code as without
//! hooks. A probe only observes: it never changes a value, a branch or the sampler's stream, so a
//! probed render gives the same bits as an unprobed one. [`Counters`] counts the work (for
//! `tessera render --stats`); `PathRecord` records a path for
//! `--debug-pixel`.
use crate::accel::TraversalCounts;
use crate::bsdf::BsdfSample;
use crate::emitter::EmitterSample;
use crate::geometry::{Interaction, ShapeKind};
use crate::light::LightSample;
use crate::math::Ray;
use crate::scene::Scene;
use crate::Color;
use glam::{Vec2, Vec3};

/// Why a ray was traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayKind {
    /// The first segment, from the camera.
    Camera,
    /// A later segment along a BSDF-sampled direction.
    Continuation,
    /// A visibility test toward a sampled point on a light.
    Shadow,
}

/// Why a path stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathEnd {
    /// The ray left the scene.
    Escaped,
    /// A camera ray met an emitter while emitters are hidden.
    HiddenEmitter,
    /// The next segment would exceed `max_depth`.
    MaxDepth,
    /// The next segment could only add light that no ray can reach (no hittable emitter, or
    /// emitter sampling at this vertex already counted it): not traced.
    NothingAhead,
    /// The BSDF produced no direction.
    BsdfSampleFailed,
    /// Russian roulette ended the path.
    Roulette,
    /// The throughput became zero or non-finite.
    ZeroThroughput,
}

/// What a path met in a participating medium (`volpath`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MediumEvent {
    /// A free-flight sample collided inside the medium: a real scattering event.
    Scatter,
    /// A free-flight sample passed the whole segment to the next surface (or to infinity).
    Pass,
    /// The path crossed a `null` surface (a medium's boundary) without scattering.
    NullCrossing,
    /// A shadow ray crossed a `null` surface.
    ShadowNullCrossing,
    /// Delta tracking in a heterogeneous medium met a null collision (a tentative collision
    /// that did not scatter).
    NullCollision,
    /// Ratio tracking on a shadow ray through a heterogeneous medium met a tentative collision.
    ShadowNullCollision,
}

/// Receives the events of one sample's path. Every method defaults to doing nothing.
#[allow(unused_variables)]
pub trait Probe {
    /// Whether the probe observes more than the rays cast: false only for one whose every
    /// method but [`Probe::ray`] is the default (no counting, no recording), so that a render
    /// loop may skip the calls it would ignore (see `RenderJob::pixel_alone`'s batches of
    /// escaping camera rays); such a loop still reports every ray.
    const OBSERVES: bool = true;
    /// Casts a camera or continuation ray: the scene's closest hit. A probe may count the
    /// traversal's work; the result must be the scene's.
    #[inline(always)]
    fn intersect(&mut self, scene: &Scene, ray: &Ray) -> Option<Interaction> {
        scene.intersect(ray)
    }
    /// Casts a shadow ray: whether anything blocks it (same contract as [`Probe::intersect`]).
    #[inline(always)]
    fn occluded(&mut self, scene: &Scene, ray: &Ray) -> bool {
        scene.occluded(ray)
    }
    /// The camera sample: film position (pixels) and the generated ray.
    #[inline(always)]
    fn camera(&mut self, pos: Vec2, ray: &Ray) {}
    /// A ray was traced; for camera and continuation rays `hit` follows.
    #[inline(always)]
    fn ray(&mut self, kind: RayKind) {}
    /// What a camera or continuation ray met (`None`: it escaped along `dir`, not normalized).
    #[inline(always)]
    fn hit(&mut self, scene: &Scene, si: Option<&Interaction>, dir: Vec3) {}
    /// A shadow ray's outcome.
    #[inline(always)]
    fn shadow(&mut self, blocked: bool) {}
    /// An environment emitter was evaluated (radiance or density) for a direction.
    #[inline(always)]
    fn env_lookup(&mut self) {}
    /// Light found by a traced ray: emitted radiance, its weight and what it added.
    #[inline(always)]
    fn emission(&mut self, le: Color, weight: f32, contribution: Color) {}
    /// Emitter `index` (picked with probability `select_pdf`) was sampled.
    #[inline(always)]
    fn emitter_sample(&mut self, index: usize, select_pdf: f32, s: Option<&EmitterSample>) {}
    /// The BSDF was evaluated (`f cos`).
    #[inline(always)]
    fn bsdf_eval(&mut self, f: Color) {}
    /// The BSDF's density was evaluated.
    #[inline(always)]
    fn bsdf_pdf(&mut self, pdf: f32) {}
    /// An emitter sample that arrived: its MIS weight and what it added.
    #[inline(always)]
    fn light(&mut self, ls: &LightSample, weight: f32, contribution: Color) {}
    /// A multiple-importance-sampling weight was computed.
    #[inline(always)]
    fn mis_weight(&mut self) {}
    /// The BSDF was sampled (`None`: no direction); `wo` in world space; `throughput` after.
    #[inline(always)]
    fn bsdf_sample(&mut self, s: Option<&BsdfSample>, wo: Vec3, throughput: Color) {}
    /// Russian roulette with survival probability `q`; `throughput` after.
    #[inline(always)]
    fn roulette(&mut self, q: f32, survived: bool, throughput: Color) {}
    /// The path stopped.
    #[inline(always)]
    fn end(&mut self, why: PathEnd) {}
    /// A medium event (`volpath` only).
    #[inline(always)]
    fn medium(&mut self, event: MediumEvent) {}
}

/// Observes nothing: the ordinary render.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProbe;

impl Probe for NoProbe {
    const OBSERVES: bool = false;
}

/// How much work paths did, by kind. Counts are sums over samples, so they are the same for any
/// thread count or tile order.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Samples traced.
    pub samples: u64,
    /// Camera rays traced.
    pub camera_rays: u64,
    /// BSDF-sampled continuation rays traced.
    pub continuation_rays: u64,
    /// Shadow rays traced.
    pub shadow_rays: u64,
    /// Shadow rays that were blocked.
    pub shadow_blocked: u64,
    /// Camera or continuation rays that met a triangle (mesh interaction computed).
    pub triangle_hits: u64,
    /// ... that met a sphere.
    pub sphere_hits: u64,
    /// ... that met a disk (or a cylinder, the other flat-parametrised analytic shape).
    pub disk_hits: u64,
    /// ... that escaped the scene.
    pub escaped: u64,
    /// BSDF evaluations (`eval`).
    pub bsdf_evals: u64,
    /// BSDF density evaluations (`pdf`).
    pub bsdf_pdfs: u64,
    /// BSDF samples drawn.
    pub bsdf_samples: u64,
    /// Emitter samples drawn.
    pub emitter_samples: u64,
    /// MIS weights computed.
    pub mis_weights: u64,
    /// Environment evaluations (radiance or density).
    pub env_lookups: u64,
    /// Light contributions found by traced rays (emitter hit or environment).
    pub emission_hits: u64,
    /// Russian roulette decisions.
    pub roulette: u64,
    /// Paths ended by Russian roulette.
    pub roulette_kills: u64,
    /// BVH nodes visited by all rays (each a test of four child boxes).
    pub bvh_nodes: u64,
    /// BVH leaves reached by all rays.
    pub bvh_leaves: u64,
    /// Primitive blocks tested (up to four triangles, spheres or disks at once).
    pub prim_blocks: u64,
    /// Scattering events inside media (`volpath`).
    pub medium_scatters: u64,
    /// Free-flight samples that passed a whole segment of a medium.
    pub medium_passes: u64,
    /// `null` surfaces crossed by paths.
    pub null_crossings: u64,
    /// `null` surfaces crossed by shadow rays.
    pub shadow_null_crossings: u64,
    /// Null collisions of delta tracking in heterogeneous media (paths).
    pub null_collisions: u64,
    /// Tentative collisions of ratio tracking in heterogeneous media (shadow rays).
    pub shadow_null_collisions: u64,
}

impl Counters {
    /// Adds another set of counts (order does not matter).
    pub fn merge(&mut self, o: &Counters) {
        for (a, b) in self.fields_mut().into_iter().zip(o.rows()) {
            *a += b.1;
        }
    }

    /// Every count with its name, in a fixed order (for printing).
    pub fn rows(&self) -> [(&'static str, u64); 27] {
        [
            ("samples", self.samples),
            ("camera rays", self.camera_rays),
            ("continuation rays", self.continuation_rays),
            ("shadow rays", self.shadow_rays),
            ("shadow rays blocked", self.shadow_blocked),
            ("triangle hits", self.triangle_hits),
            ("sphere hits", self.sphere_hits),
            ("disk hits", self.disk_hits),
            ("escaped rays", self.escaped),
            ("bsdf evals", self.bsdf_evals),
            ("bsdf pdfs", self.bsdf_pdfs),
            ("bsdf samples", self.bsdf_samples),
            ("emitter samples", self.emitter_samples),
            ("mis weights", self.mis_weights),
            ("env lookups", self.env_lookups),
            ("emission hits", self.emission_hits),
            ("roulette decisions", self.roulette),
            ("roulette kills", self.roulette_kills),
            ("bvh nodes visited", self.bvh_nodes),
            ("bvh leaves reached", self.bvh_leaves),
            ("primitive blocks tested", self.prim_blocks),
            ("medium scatters", self.medium_scatters),
            ("medium passes", self.medium_passes),
            ("null crossings", self.null_crossings),
            ("shadow null crossings", self.shadow_null_crossings),
            ("null collisions", self.null_collisions),
            ("shadow null collisions", self.shadow_null_collisions),
        ]
    }

    fn fields_mut(&mut self) -> [&mut u64; 27] {
        [
            &mut self.samples,
            &mut self.camera_rays,
            &mut self.continuation_rays,
            &mut self.shadow_rays,
            &mut self.shadow_blocked,
            &mut self.triangle_hits,
            &mut self.sphere_hits,
            &mut self.disk_hits,
            &mut self.escaped,
            &mut self.bsdf_evals,
            &mut self.bsdf_pdfs,
            &mut self.bsdf_samples,
            &mut self.emitter_samples,
            &mut self.mis_weights,
            &mut self.env_lookups,
            &mut self.emission_hits,
            &mut self.roulette,
            &mut self.roulette_kills,
            &mut self.bvh_nodes,
            &mut self.bvh_leaves,
            &mut self.prim_blocks,
            &mut self.medium_scatters,
            &mut self.medium_passes,
            &mut self.null_crossings,
            &mut self.shadow_null_crossings,
            &mut self.null_collisions,
            &mut self.shadow_null_collisions,
        ]
    }
}

impl Counters {
    fn add_traversal(&mut self, c: &TraversalCounts) {
        self.bvh_nodes += c.nodes;
        self.bvh_leaves += c.leaves;
        self.prim_blocks += c.blocks;
    }
}

impl Probe for Counters {
    fn intersect(&mut self, scene: &Scene, ray: &Ray) -> Option<Interaction> {
        // The cast is repeated with counters rather than building the interaction from the
        // counted cast: a second caller of the interaction code made the compiler stop inlining
        // it into the ordinary cast (+0.6% instructions on every render). Statistics runs pay
        // for the traversal twice instead.
        let mut c = TraversalCounts::default();
        scene.intersect_hit_counted(ray, &mut c);
        self.add_traversal(&c);
        scene.intersect(ray)
    }
    fn occluded(&mut self, scene: &Scene, ray: &Ray) -> bool {
        let mut c = TraversalCounts::default();
        let blocked = scene.occluded_counted(ray, &mut c);
        self.add_traversal(&c);
        blocked
    }
    fn camera(&mut self, _: Vec2, _: &Ray) {
        self.samples += 1;
    }
    fn ray(&mut self, kind: RayKind) {
        match kind {
            RayKind::Camera => self.camera_rays += 1,
            RayKind::Continuation => self.continuation_rays += 1,
            RayKind::Shadow => self.shadow_rays += 1,
        }
    }
    fn hit(&mut self, scene: &Scene, si: Option<&Interaction>, _: Vec3) {
        let Some(si) = si else {
            self.escaped += 1;
            return;
        };
        match scene.shapes[si.shape as usize].kind {
            ShapeKind::Mesh(_) => self.triangle_hits += 1,
            ShapeKind::Sphere(_) => self.sphere_hits += 1,
            ShapeKind::Disk(_) | ShapeKind::Cylinder(_) | ShapeKind::Curve(_) => {
                self.disk_hits += 1
            }
        }
    }
    fn shadow(&mut self, blocked: bool) {
        self.shadow_blocked += blocked as u64;
    }
    fn env_lookup(&mut self) {
        self.env_lookups += 1;
    }
    fn emission(&mut self, _: Color, _: f32, _: Color) {
        self.emission_hits += 1;
    }
    fn emitter_sample(&mut self, _: usize, _: f32, _: Option<&EmitterSample>) {
        self.emitter_samples += 1;
    }
    fn bsdf_eval(&mut self, _: Color) {
        self.bsdf_evals += 1;
    }
    fn bsdf_pdf(&mut self, _: f32) {
        self.bsdf_pdfs += 1;
    }
    fn mis_weight(&mut self) {
        self.mis_weights += 1;
    }
    fn bsdf_sample(&mut self, _: Option<&BsdfSample>, _: Vec3, _: Color) {
        self.bsdf_samples += 1;
    }
    fn roulette(&mut self, _: f32, survived: bool, _: Color) {
        self.roulette += 1;
        self.roulette_kills += !survived as u64;
    }
    fn medium(&mut self, event: MediumEvent) {
        match event {
            MediumEvent::Scatter => self.medium_scatters += 1,
            MediumEvent::Pass => self.medium_passes += 1,
            MediumEvent::NullCrossing => self.null_crossings += 1,
            MediumEvent::ShadowNullCrossing => self.shadow_null_crossings += 1,
            MediumEvent::NullCollision => self.null_collisions += 1,
            MediumEvent::ShadowNullCollision => self.shadow_null_collisions += 1,
        }
    }
}

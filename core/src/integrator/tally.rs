//! [`RayTally`]: a probe that counts the rays a render loop's samples cast, passing every event
//! on to another probe.
//!
//! The count is how adaptive sampling learns what a pixel's samples cost: a pixel whose paths
//! go through glass casts many rays per sample, one that sees the sky casts one. A count, not a
//! time, so that the same samples give the same plan on any machine. The tally lives in a
//! [`Cell`] outside the probe, so that a render loop's per-sample callback, which runs while
//! the integrator holds the probe, can read how many rays the samples before it cast.
use super::probe::{MediumEvent, PathEnd, Probe, RayKind};
use crate::bsdf::BsdfSample;
use crate::emitter::EmitterSample;
use crate::geometry::Interaction;
use crate::light::LightSample;
use crate::math::Ray;
use crate::scene::Scene;
use crate::Color;
use core::cell::Cell;
use glam::{Vec2, Vec3};

/// Counts the rays cast (every [`Probe::ray`]) into `rays` and passes every event to `inner`.
/// It observes what `inner` observes ([`Probe::OBSERVES`]): rays are reported even where a
/// render loop skips the other calls.
#[derive(Debug)]
pub struct RayTally<'a, P> {
    inner: &'a mut P,
    rays: &'a Cell<u64>,
}

impl<'a, P: Probe> RayTally<'a, P> {
    /// A tally adding to `rays`, passing events to `inner`.
    pub fn new(inner: &'a mut P, rays: &'a Cell<u64>) -> Self {
        RayTally { inner, rays }
    }
}

impl<P: Probe> Probe for RayTally<'_, P> {
    const OBSERVES: bool = P::OBSERVES;
    #[inline(always)]
    fn intersect(&mut self, scene: &Scene, ray: &Ray) -> Option<Interaction> {
        self.inner.intersect(scene, ray)
    }
    #[inline(always)]
    fn occluded(&mut self, scene: &Scene, ray: &Ray) -> bool {
        self.inner.occluded(scene, ray)
    }
    #[inline(always)]
    fn camera(&mut self, pos: Vec2, ray: &Ray) {
        self.inner.camera(pos, ray)
    }
    #[inline(always)]
    fn ray(&mut self, kind: RayKind) {
        self.rays.set(self.rays.get() + 1);
        self.inner.ray(kind)
    }
    #[inline(always)]
    fn hit(&mut self, scene: &Scene, si: Option<&Interaction>, dir: Vec3) {
        self.inner.hit(scene, si, dir)
    }
    #[inline(always)]
    fn shadow(&mut self, blocked: bool) {
        self.inner.shadow(blocked)
    }
    #[inline(always)]
    fn env_lookup(&mut self) {
        self.inner.env_lookup()
    }
    #[inline(always)]
    fn emission(&mut self, le: Color, weight: f32, contribution: Color) {
        self.inner.emission(le, weight, contribution)
    }
    #[inline(always)]
    fn emitter_sample(&mut self, index: usize, select_pdf: f32, s: Option<&EmitterSample>) {
        self.inner.emitter_sample(index, select_pdf, s)
    }
    #[inline(always)]
    fn bsdf_eval(&mut self, f: Color) {
        self.inner.bsdf_eval(f)
    }
    #[inline(always)]
    fn bsdf_pdf(&mut self, pdf: f32) {
        self.inner.bsdf_pdf(pdf)
    }
    #[inline(always)]
    fn light(&mut self, ls: &LightSample, weight: f32, contribution: Color) {
        self.inner.light(ls, weight, contribution)
    }
    #[inline(always)]
    fn mis_weight(&mut self) {
        self.inner.mis_weight()
    }
    #[inline(always)]
    fn bsdf_sample(&mut self, s: Option<&BsdfSample>, wo: Vec3, throughput: Color) {
        self.inner.bsdf_sample(s, wo, throughput)
    }
    #[inline(always)]
    fn roulette(&mut self, q: f32, survived: bool, throughput: Color) {
        self.inner.roulette(q, survived, throughput)
    }
    #[inline(always)]
    fn end(&mut self, why: PathEnd) {
        self.inner.end(why)
    }
    #[inline(always)]
    fn medium(&mut self, event: MediumEvent) {
        self.inner.medium(event)
    }
}

//! The path tracer started from a camera ray already cast: what a render loop that casts a
//! batch of camera rays before following their paths calls for each ray that met a surface
//! (see `escapes.rs`). The value is [`PathIntegrator::li_probed`]'s for the same ray and
//! sampler, bit for bit: the same steps, the first one given its hit instead of casting.
use super::path::{alive, Strategy, BSDF, EMITTER, HALF, MIS};
use super::path_state::PathState;
use super::probe::{PathEnd, Probe};
use super::PathIntegrator;
use crate::geometry::Interaction;
use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

impl PathIntegrator {
    /// Radiance along the camera ray `ray`, whose closest hit is `hit` (what
    /// `scene.intersect(&ray)` gives); the same value as [`PathIntegrator::li_probed`], which
    /// would cast it. `probe` is not told about the camera ray's cast.
    #[inline]
    pub fn li_from_camera_hit<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        hit: Option<Interaction>,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        match self.strategy {
            Strategy::Bsdf => self.trace_from::<BSDF, S, P>(scene, ray, hit, sampler, probe),
            Strategy::Emitter => self.trace_from::<EMITTER, S, P>(scene, ray, hit, sampler, probe),
            Strategy::Half => self.trace_from::<HALF, S, P>(scene, ray, hit, sampler, probe),
            Strategy::Mis => self.trace_from::<MIS, S, P>(scene, ray, hit, sampler, probe),
        }
    }

    /// `trace` with the first ray's hit given: its first step, then the loop.
    #[inline(always)]
    fn trace_from<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        hit: Option<Interaction>,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let mut result = Color::ZERO;
        if self.max_depth == Some(0) {
            probe.end(PathEnd::MaxDepth);
            return result;
        }
        let mut path = PathState::start(ray);
        let Some(si) = self.arrive_at::<ST, P>(scene, &path, hit, &mut result, probe) else {
            return result;
        };
        let whole = |t| t;
        if self.scatter::<ST, S, P>(scene, &si, &mut path, &mut result, sampler, probe)
            && self.roulette(&mut path, sampler, probe, whole)
            && alive(&path, probe)
        {
            self.follow::<ST, S, P, _>(scene, &mut path, &mut result, sampler, probe, whole);
        }
        result
    }
}

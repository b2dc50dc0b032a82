//! The two halves path reuse's group estimator (`reuse.rs`) splits a pixel's path into, each
//! composed from the path tracer's own steps (`path.rs`): the prefix, from the camera ray up to
//! the second vertex, and the suffix, which goes on from that vertex. Run one after the other on
//! the same state and sampler they are the ordinary path, bit for bit; the group estimator runs
//! the suffix from a throughput of 1 where it shares the second vertex's light.
use super::path::PathIntegrator;
use super::path_state::{alive, PathState};
use super::probe::{PathEnd, Probe};
use crate::geometry::{Interaction, Partials};
use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

/// What a prefix leaves: the first vertex where the path sampled its BSDF, and the vertex that
/// bounce reached with the state to go on from it.
#[derive(Clone, Copy, Default)]
pub(super) struct Prefix<'a> {
    /// First vertex, its BSDF index, `wi` in its shading frame and its partials (for a BSDF that reads them) (set when it has a smooth
    /// component and the path sampled its BSDF there).
    pub x: Option<(Interaction, u32, Vec3, Option<Partials<'a>>)>,
    /// Whether the bounce from `x` took a delta component.
    pub delta: bool,
    /// The second vertex (its emission already counted) and the path's state there.
    pub y: Option<(PathState, Interaction)>,
}

impl PathIntegrator {
    /// The path along the camera ray `ray` up to its second vertex, for the strategy numbered
    /// `ST`: the light found on the way (emission at both vertices, emitter sampling at the
    /// first), with the vertices and state left in `prefix`. Only for settings that
    /// [`PathIntegrator::reuses`]: then neither the depth limit nor Russian roulette can end a
    /// path before its second vertex.
    #[inline(always)]
    pub(super) fn prefix<'a, const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &'a Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
        prefix: &mut Prefix<'a>,
    ) -> Color {
        debug_assert!(self.reuses());
        let mut result = Color::ZERO;
        let mut path = PathState::start(ray);
        let Some(x) = self.arrive::<ST, P>(scene, &path, &mut result, probe) else {
            return result;
        };
        let bsdf = scene.shapes[x.shape as usize].bsdf;
        if scene.bsdf_traits(bsdf).has_smooth {
            let g = scene.partials(bsdf, &x, &path.ray);
            prefix.x = Some((x, bsdf, x.frame.to_local(x.wi), g));
        }
        if !self.scatter::<ST, S, P>(scene, &x, &mut path, &mut result, sampler, probe)
            || !self.roulette(&mut path, sampler, probe, |t| t)
        {
            return result;
        }
        prefix.delta = path.prev.is_some_and(|p| p.delta);
        // The second vertex is a sample for the neighbours too, whatever its own weight: only a
        // throughput that is not finite ends the path here.
        if !path.throughput.is_finite() {
            probe.end(PathEnd::ZeroThroughput);
            return result;
        }
        if let Some(y) = self.arrive::<ST, P>(scene, &path, &mut result, probe) {
            prefix.y = Some((path, y));
        }
        result
    }

    /// The rest of a path from the vertex `y` its state `path` reached (a prefix's second
    /// vertex, its emission counted), for the strategy numbered `ST`: the light found from `y`
    /// on. Russian roulette sees the throughput times `rr_scale`.
    #[inline(always)]
    pub(super) fn suffix<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        mut path: PathState,
        y: &Interaction,
        rr_scale: Color,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let mut result = Color::ZERO;
        let sees = |t: Color| t * rr_scale;
        if self.scatter::<ST, S, P>(scene, y, &mut path, &mut result, sampler, probe)
            && self.roulette(&mut path, sampler, probe, sees)
            && alive(&path, probe)
        {
            self.follow::<ST, S, P, _>(scene, &mut path, &mut result, sampler, probe, sees);
        }
        result
    }
}

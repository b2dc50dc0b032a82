//! Integrators: a closed enum; each estimates the radiance arriving along one camera ray.
mod direct;
mod mis;
mod path;
mod path_state;
mod probe;
mod record;
mod reuse;

pub use direct::DirectIntegrator;
pub use mis::{balance_heuristic, power_heuristic, Heuristic};
pub use path::{PathIntegrator, Strategy};
pub use probe::{Counters, NoProbe, PathEnd, Probe, RayKind};
pub use record::{Event, PathRecord};
pub use reuse::{GROUP, GROUP_H, GROUP_W};

use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

/// The light transport algorithms.
#[derive(Clone, Debug)]
pub enum Integrator {
    /// Unidirectional path tracing (`path_mats`, `path_ems`, `path_half`, `path_mis` / `path`).
    Path(PathIntegrator),
    /// Direct illumination (`direct`, `direct_ems`, `direct_mats`, `direct_mis`).
    Direct(DirectIntegrator),
}

impl Integrator {
    /// Radiance arriving along `ray` (one sample; may be non-finite only through broken input,
    /// which the caller drops and counts).
    #[inline]
    pub fn li<S: Sampler>(&self, scene: &Scene, ray: Ray, sampler: &mut S) -> Color {
        match self {
            Integrator::Path(p) => p.li(scene, ray, sampler),
            Integrator::Direct(d) => d.li(scene, ray, sampler),
        }
    }

    /// [`Integrator::li`], telling `probe` about the work done; the same value for any probe.
    #[inline]
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        match self {
            Integrator::Path(p) => p.li_probed(scene, ray, sampler, probe),
            Integrator::Direct(d) => d.li_probed(scene, ray, sampler, probe),
        }
    }
}

//! Integrators: a closed enum; each estimates the radiance arriving along one camera ray.
mod direct;
mod light;
mod mis;
mod path;

pub use direct::DirectIntegrator;
pub use light::{emission_along, sample_light, LightSample};
pub use mis::{balance_heuristic, power_heuristic, Heuristic};
pub use path::{PathIntegrator, Strategy};

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
}

//! What a wrapping integrator asks of the integrator it wraps: the radiance along a camera ray,
//! as a trait, so that the wrapper (`moment`) is written over any integrator type and its file
//! need not know the `Integrator` enum that holds it (the enum implements the trait).
use super::probe::Probe;
use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

/// An estimator of the radiance arriving along a camera ray.
pub trait Radiance {
    /// Radiance along `ray` (one sample), telling `probe` about the work done.
    fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color;
}

//! What one emitter sample delivers to an integrator: the estimate and the densities both
//! strategies would have had. Its own file so that the probes, which are told about it, and the
//! sampling code, which tells them, both depend on it and not on each other.
use crate::Color;

/// One emitter sample, already tested for visibility.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// `f(wi, wo) cos * Le / (light pdf * selection probability)`: the unweighted estimate.
    pub value: Color,
    /// Density of emitter sampling for this direction, selection included (solid angle).
    pub light_pdf: f32,
    /// Density with which the BSDF would have sampled the same direction (0 when the caller
    /// did not ask for it, or for a delta light).
    pub bsdf_pdf: f32,
    /// Whether the light is a delta distribution (BSDF sampling cannot find it).
    pub delta: bool,
}

//! What sampling any phase function returns. Its own file so that the phase function kinds take
//! it from below instead of from the enum that holds them.
use glam::Vec3;

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug)]
pub struct PhaseSample {
    /// Unit direction toward the next vertex (world space).
    pub wo: Vec3,
    /// Solid-angle density of `wo`.
    pub pdf: f32,
    /// The phase function's value over `pdf`: what the sample multiplies a path's throughput
    /// by (1 for a function sampled exactly by its density).
    pub weight: f32,
}

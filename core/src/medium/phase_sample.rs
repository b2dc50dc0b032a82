//! What sampling any phase function returns. Its own file so that the phase function kinds take
//! it from below instead of from the enum that holds them.
use glam::Vec3;

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug)]
pub struct PhaseSample {
    /// Unit direction toward the next vertex (world space).
    pub wo: Vec3,
    /// Solid-angle density of `wo`, equal to the phase function's value there (weight 1).
    pub pdf: f32,
}

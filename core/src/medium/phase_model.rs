//! What every phase function offers, as a trait: so that a function made of other phase
//! functions (`blend.rs`) is written over any of them, below the enum that holds them all
//! instead of beside it.
use super::phase_sample::PhaseSample;
use glam::{Vec2, Vec3};

/// A phase function (conventions in `phase.rs`).
pub trait PhaseModel {
    /// Value of scattering from `wi` toward `wo`, per steradian.
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32;
    /// Solid-angle density with which `sample` returns `wo` for `wi`.
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32;
    /// Samples `wo` for `wi` from two uniform numbers.
    fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample;
}

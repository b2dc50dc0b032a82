//! Phase functions: the angular distribution of light scattered at a point in a medium, a closed
//! enum over the kinds in `isotropic.rs` and `hg.rs`.
//!
//! Conventions (Mitsuba 3's): `wi` is the unit direction back toward where the light goes (the
//! previous path vertex), `wo` the unit direction toward the next vertex, both in world space.
//! Every phase function here is normalised over the sphere and sampled exactly by its density,
//! so a sample's weight is 1 and only its density is returned.
use super::hg::HenyeyGreenstein;
use super::isotropic::Isotropic;
use super::phase_sample::PhaseSample;
use glam::{Vec2, Vec3};

/// Phase functions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PhaseFunction {
    /// Uniform over the sphere (`isotropic`).
    Isotropic(Isotropic),
    /// Henyey-Greenstein with asymmetry `g` (`hg`).
    Hg(HenyeyGreenstein),
}

impl Default for PhaseFunction {
    /// `isotropic`, the phase function of a medium that names none (as in Mitsuba 3).
    fn default() -> Self {
        PhaseFunction::Isotropic(Isotropic)
    }
}

impl PhaseFunction {
    /// Value (and density) of scattering from `wi` toward `wo`, per steradian.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        match self {
            PhaseFunction::Isotropic(p) => p.eval(),
            PhaseFunction::Hg(p) => p.eval(wi, wo),
        }
    }
    /// Samples `wo` for `wi` from two uniform numbers.
    #[inline]
    pub fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        match self {
            PhaseFunction::Isotropic(p) => p.sample(u),
            PhaseFunction::Hg(p) => p.sample(wi, u),
        }
    }
}

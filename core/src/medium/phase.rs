//! Phase functions: the angular distribution of light scattered at a point in a medium, a closed
//! enum over the kinds in `isotropic.rs`, `hg.rs`, `rayleigh.rs`, `tabulated.rs`, `blend.rs` and
//! `sggx.rs`.
//!
//! Conventions (Mitsuba 3's): `wi` is the unit direction back toward where the light goes (the
//! previous path vertex), `wo` the unit direction toward the next vertex, both in world space.
//! Every phase function here is normalised over the sphere. A sample returns its density and its
//! weight (value over density), which is 1 for the kinds sampled exactly by their density (all
//! of them so far: a blend of such kinds is too).
use super::blend::Blend;
use super::hg::HenyeyGreenstein;
use super::isotropic::Isotropic;
use super::phase_model::PhaseModel;
use super::phase_sample::PhaseSample;
use super::rayleigh::Rayleigh;
use super::sggx::Sggx;
use super::tabulated::Tabulated;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// Phase functions.
#[derive(Clone, Debug, PartialEq)]
pub enum PhaseFunction {
    /// Uniform over the sphere (`isotropic`).
    Isotropic(Isotropic),
    /// Henyey-Greenstein with asymmetry `g` (`hg`).
    Hg(HenyeyGreenstein),
    /// Rayleigh scattering (`rayleigh`).
    Rayleigh(Rayleigh),
    /// A table over the cosine of the scattering angle (`tabphase`; boxed, as it holds the table).
    Tabulated(Box<Tabulated>),
    /// A constant-weight blend of two phase functions (`blendphase`).
    Blend(Blend<PhaseFunction>),
    /// SGGX microflakes of one matrix (`sggx`; the matrix at the scattering point).
    Sggx(Sggx),
}

impl Default for PhaseFunction {
    /// `isotropic`, the phase function of a medium that names none (as in Mitsuba 3).
    fn default() -> Self {
        PhaseFunction::Isotropic(Isotropic)
    }
}

impl PhaseModel for PhaseFunction {
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        PhaseFunction::eval(self, wi, wo)
    }
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        PhaseFunction::pdf(self, wi, wo)
    }
    #[inline]
    fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        PhaseFunction::sample(self, wi, u)
    }
}

impl PhaseFunction {
    /// Value of scattering from `wi` toward `wo`, per steradian.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        match self {
            PhaseFunction::Isotropic(p) => p.eval(),
            PhaseFunction::Hg(p) => p.eval(wi, wo),
            PhaseFunction::Rayleigh(p) => p.eval(wi, wo),
            PhaseFunction::Tabulated(p) => p.eval(wi, wo),
            PhaseFunction::Blend(p) => p.eval(wi, wo),
            PhaseFunction::Sggx(p) => p.eval(wi, wo),
        }
    }
    /// Solid-angle density with which [`PhaseFunction::sample`] returns `wo` for `wi`.
    #[inline]
    pub fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        match self {
            PhaseFunction::Blend(p) => p.pdf(wi, wo),
            // Sampled exactly: the density is the value.
            _ => self.eval(wi, wo),
        }
    }
    /// Samples `wo` for `wi` from two uniform numbers.
    #[inline]
    pub fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        match self {
            PhaseFunction::Isotropic(p) => p.sample(u),
            PhaseFunction::Hg(p) => p.sample(wi, u),
            PhaseFunction::Rayleigh(p) => p.sample(wi, u),
            PhaseFunction::Tabulated(p) => p.sample(wi, u),
            PhaseFunction::Blend(p) => p.sample(wi, u),
            PhaseFunction::Sggx(p) => p.sample(wi, u),
        }
    }
}

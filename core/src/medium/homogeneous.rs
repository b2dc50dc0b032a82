//! A homogeneous medium (`homogeneous`, Mitsuba 3's): extinction `sigma_t` and single-scattering
//! albedo constant throughout, per colour channel, and one phase function.
//!
//! Light travelling a distance `d` through it keeps `exp(-sigma_t d)` (Beer-Lambert); at a
//! collision a fraction `albedo` scatters (`sigma_s = albedo sigma_t`) and the rest is
//! absorbed. The loader folds Mitsuba's `scale` into `sigma_t`.
use super::phase::PhaseFunction;
use crate::Color;

/// A medium of constant extinction and albedo.
#[derive(Clone, Debug)]
pub struct Homogeneous {
    /// Extinction coefficient per channel, in inverse scene units (scale applied), >= 0.
    pub sigma_t: Color,
    /// Single-scattering albedo per channel.
    pub albedo: Color,
    /// How scattered light is distributed over directions.
    pub phase: PhaseFunction,
    /// Whether scattering events in it sample emitters (shadow rays from inside the medium).
    pub sample_emitters: bool,
}

impl Homogeneous {
    /// Scattering coefficient `albedo * sigma_t`.
    #[inline]
    pub fn sigma_s(&self) -> Color {
        self.albedo * self.sigma_t
    }
    /// Fraction of light kept over a distance `d` (which may be infinite): `exp(-sigma_t d)`
    /// per channel, 1 where `sigma_t` is 0.
    #[inline]
    pub fn transmittance(&self, d: f32) -> Color {
        transmittance(self.sigma_t, d)
    }
}

/// `exp(-sigma_t d)` per channel, exactly 1 where `sigma_t` is 0 (also for infinite `d`).
#[inline]
pub(super) fn transmittance(sigma_t: Color, d: f32) -> Color {
    let one = |s: f32| if s > 0.0 { libm::expf(-s * d) } else { 1.0 };
    Color::new(one(sigma_t.x), one(sigma_t.y), one(sigma_t.z))
}

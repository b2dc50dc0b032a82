//! The Rayleigh phase function (`rayleigh`, Mitsuba 3's): scattering by particles much smaller
//! than the wavelength, `p(c) = 3 (1 + c^2) / (16 pi)` per steradian for the cosine `c` of the
//! scattering angle. It is symmetric between forward and backward and has no parameters.
//!
//! Sampling is exact: the cumulative distribution of `c` over [-1, 1] is
//! `F(c) = 1/2 + 3 c / 8 + c^3 / 8`, so `F(c) = u` is the cubic `c^3 + 3 c - (8 u - 4) = 0`,
//! whose one real root Cardano's formula gives with `z = 4 u - 2`:
//! `c = cbrt(z + sqrt(z^2 + 1)) + cbrt(z - sqrt(z^2 + 1))`.
use super::phase_sample::PhaseSample;
use crate::math::{sincos_turns, sqrt, Frame, PI};
use glam::{Vec2, Vec3};

/// Rayleigh scattering.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rayleigh;

impl Rayleigh {
    /// The density for cosine `c` of the scattering angle.
    #[inline]
    pub fn eval_cos(&self, c: f32) -> f32 {
        3.0 / (16.0 * PI) * (1.0 + c * c)
    }
    /// Value (and density) of scattering from `wi` toward `wo`.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.eval_cos(-wi.dot(wo))
    }
    /// Samples `wo` for `wi` from two uniform numbers (weight 1).
    #[inline]
    pub fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        let z = 4.0 * u.x - 2.0;
        let r = sqrt(z * z + 1.0);
        let c = (libm::cbrtf(z + r) + libm::cbrtf(z - r)).clamp(-1.0, 1.0);
        let sin = sqrt((1.0 - c * c).max(0.0));
        let (sp, cp) = sincos_turns(u.y);
        let wo = Frame::from_normal(-wi).to_world(Vec3::new(sin * cp, sin * sp, c));
        PhaseSample {
            wo,
            pdf: self.eval_cos(c),
            weight: 1.0,
        }
    }
}

//! The Henyey-Greenstein phase function (`hg`), as Mitsuba 3 defines it.
//!
//! With `c` the cosine between the direction of propagation (`-wi`) and `wo`:
//! `p(c) = (1 - g^2) / (4 pi (1 + g^2 - 2 g c)^(3/2))`. `g` in (-1, 1) is the mean cosine:
//! positive scatters forward, negative backward, 0 is isotropic. Sampling inverts the
//! cumulative distribution of `c` in closed form; for |g| below 1e-3 the inversion loses its
//! digits and the uniform sphere (the limit) is used instead, whose density the evaluation then
//! also returns, so that the sample's density is always the function's value.
use super::phase_sample::PhaseSample;
use crate::math::{sincos_turns, sqrt, Frame, PI};
use glam::{Vec2, Vec3};

/// Below this |g| the function is treated as isotropic.
const NEAR_ISOTROPIC: f32 = 1e-3;

/// Henyey-Greenstein scattering with asymmetry `g`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    /// Mean cosine of the scattering angle, in (-1, 1).
    pub g: f32,
}

impl HenyeyGreenstein {
    /// The density for cosine `c` between the propagation direction and `wo`.
    #[inline]
    pub fn eval_cos(&self, c: f32) -> f32 {
        let g = self.g;
        if g.abs() < NEAR_ISOTROPIC {
            return 0.25 / PI;
        }
        let denom = 1.0 + g * g - 2.0 * g * c;
        (1.0 - g * g) / (4.0 * PI * denom * sqrt(denom.max(0.0)))
    }
    /// Value (and density) of scattering from `wi` toward `wo`.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.eval_cos(-wi.dot(wo))
    }
    /// Samples `wo` for `wi` from two uniform numbers.
    #[inline]
    pub fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        let g = self.g;
        let c = if g.abs() < NEAR_ISOTROPIC {
            1.0 - 2.0 * u.x
        } else {
            let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
            ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
        };
        let sin = sqrt((1.0 - c * c).max(0.0));
        let (sp, cp) = sincos_turns(u.y);
        let frame = Frame::from_normal(-wi);
        let wo = frame.to_world(Vec3::new(sin * cp, sin * sp, c));
        PhaseSample {
            wo,
            pdf: self.eval_cos(c),
            weight: 1.0,
        }
    }
}

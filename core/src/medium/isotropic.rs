//! The isotropic phase function (`isotropic`): every direction equally likely, 1 / (4 pi) per
//! steradian. It has no parameters.
use super::phase_sample::PhaseSample;
use crate::math::PI;
use crate::sampling::warp::square_to_uniform_sphere;
use glam::Vec2;

/// Uniform scattering over the sphere.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Isotropic;

impl Isotropic {
    /// `1 / (4 pi)`.
    #[inline]
    pub fn eval(&self) -> f32 {
        0.25 / PI
    }
    /// A uniform direction on the sphere.
    #[inline]
    pub fn sample(&self, u: Vec2) -> PhaseSample {
        PhaseSample {
            wo: square_to_uniform_sphere(u),
            pdf: self.eval(),
            weight: 1.0,
        }
    }
}

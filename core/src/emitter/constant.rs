//! Constant environment: the same radiance from every direction at infinity.
//!
//! Scene parameters (`<emitter type="constant">`): `radiance` (rgb, default 1). Sampled uniformly
//! over the sphere of directions.
use super::sample::EmitterSample;
use crate::geometry::Interaction;
use crate::sampling::warp::{square_to_uniform_sphere, uniform_sphere_pdf};
use crate::Color;
use glam::Vec2;

/// A uniform environment.
#[derive(Clone, Debug)]
pub struct ConstantEnv {
    /// Radiance arriving from every direction.
    pub radiance: Color,
}

impl ConstantEnv {
    /// A uniformly distributed direction.
    pub fn sample(&self, _it: &Interaction, u: Vec2) -> Option<EmitterSample> {
        let wo = square_to_uniform_sphere(u);
        let pdf = uniform_sphere_pdf();
        Some(EmitterSample {
            wo,
            target: None,
            weight: self.radiance / pdf,
            pdf,
            delta: false,
        })
    }
    /// Density of `sample` for any direction.
    pub fn pdf(&self) -> f32 {
        uniform_sphere_pdf()
    }
}

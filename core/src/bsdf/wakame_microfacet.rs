//! Wakame's Beckmann microfacet over diffuse (`microfacet`). Not implemented yet: every method reports no scattering.
use super::BsdfSample;
use crate::Color;
use glam::{Vec2, Vec3};

/// Wakame's Beckmann microfacet over diffuse (`microfacet`).
#[derive(Clone, Debug)]
pub struct WakameMicrofacet {}

impl WakameMicrofacet {
    /// `f(wi, wo) |cos theta_o|`.
    pub fn eval(&self, _wi: Vec3, _wo: Vec3, _uv: Vec2) -> Color {
        Color::ZERO
    }
    /// Density of the smooth components.
    pub fn pdf(&self, _wi: Vec3, _wo: Vec3, _uv: Vec2) -> f32 {
        0.0
    }
    /// Samples an outgoing direction.
    pub fn sample(&self, _wi: Vec3, _u1: f32, _u2: Vec2, _uv: Vec2) -> Option<BsdfSample> {
        None
    }
    /// Whether any component is smooth.
    pub fn has_smooth(&self) -> bool {
        false
    }
    /// Whether any component is a delta distribution.
    pub fn has_delta(&self) -> bool {
        false
    }
}

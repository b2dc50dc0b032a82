//! Nori's perfect mirror (`mirror`): every ray is reflected about the normal with weight 1.
//! One-sided, as in Nori (nothing is reflected from the back).
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/wakame.rs`.
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::Color;
use glam::{Vec2, Vec3};

/// A perfect mirror.
#[derive(Clone, Debug, Default)]
pub struct Mirror {}

impl Mirror {
    /// A delta lobe has no smooth part: 0.
    pub fn eval(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> Color {
        Color::ZERO
    }
    /// A delta lobe has no smooth density: 0.
    pub fn pdf(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> f32 {
        0.0
    }
    /// The mirror direction `(-x, -y, z)` with weight 1 and probability 1 (front side only).
    pub fn sample(&self, wi: Vec3, _u1: f32, _u2: Vec2, _at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        Some(BsdfSample::delta(
            Vec3::new(-wi.x, -wi.y, wi.z),
            Color::ONE,
            1.0,
        ))
    }
    /// No smooth component.
    pub fn has_smooth(&self) -> bool {
        false
    }
    /// The reflection is a delta distribution.
    pub fn has_delta(&self) -> bool {
        true
    }
}

//! Linear polarizer (Mitsuba 3's `polarizer`) as Mitsuba 3's unpolarized (RGB) variants
//! render it: a sheet that light passes straight through, keeping half of it (an ideal
//! polarizer passes half of unpolarized light) times its transmittance.
//!
//! Its scene parameters are declared with its loader, in `scene/src/materials/polarized.rs`;
//! the polarizer's angle matters only to polarized light, which Tessera does not carry.
//!
//! Both sides behave alike. There is no smooth component: `eval` and `pdf` are zero, and
//! `sample` always returns the pass-through `wo = -wi` as a delta component of probability 1,
//! weight `transmittance / 2`, `eta` 1, as `mask` does for its transparent part. Emitter
//! sampling therefore does not look through it (its shadow rays stop at the sheet, as
//! Mitsuba 3's do); light behind it is found by the continued path.
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Linear polarizer (`polarizer`) seen through unpolarized light.
#[derive(Clone, Debug)]
pub struct Polarizer {
    /// Factor on the light that passes (per channel).
    pub transmittance: Texture,
}

impl Polarizer {
    /// No smooth component.
    pub fn eval(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> Color {
        Color::ZERO
    }
    /// No smooth component.
    pub fn pdf(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> f32 {
        0.0
    }
    /// The straight pass-through, weighted `transmittance / 2`.
    pub fn sample(&self, wi: Vec3, _u1: f32, _u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        let weight = self.transmittance.eval(at) * 0.5;
        if !weight.is_finite() {
            return None;
        }
        Some(BsdfSample::delta(-wi, weight, 1.0))
    }
    /// No smooth component.
    pub fn has_smooth(&self) -> bool {
        false
    }
    /// The pass-through is a delta component.
    pub fn has_delta(&self) -> bool {
        true
    }
}

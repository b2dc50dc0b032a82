//! The null BSDF (Mitsuba 3's `null`): a surface that does not interact with light at all. Its
//! use is to bound a participating medium: the shape names the media on its sides, and light
//! crosses it unchanged.
//!
//! It has no parameters (its loader is in `scene/src/materials/basic.rs`). `eval` and `pdf` are
//! zero; `sample` returns the pass-through `wo = -wi`, weight 1, probability 1, `eta` 1, as a
//! delta component, so `path` follows it like a sheet of index-matched glass. `volpath` treats
//! it as Mitsuba 3 does: crossing it is not a scattering event (the path's depth does not
//! grow, emitter hits keep the weights of the last real vertex) and shadow rays pass through it.
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::Color;
use glam::{Vec2, Vec3};

/// A surface that light passes through unchanged (`null`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Null;

impl Null {
    /// No smooth component.
    pub fn eval(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> Color {
        Color::ZERO
    }
    /// No smooth component.
    pub fn pdf(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> f32 {
        0.0
    }
    /// The straight pass-through, weight 1.
    pub fn sample(&self, wi: Vec3, _u1: f32, _u2: Vec2, _at: ShadingPoint) -> Option<BsdfSample> {
        Some(BsdfSample::delta(-wi, Color::ONE, 1.0))
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

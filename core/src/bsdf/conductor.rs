//! Smooth metal: a perfect mirror weighted by the complex Fresnel reflectance (Mitsuba 3's
//! `conductor`). One-sided: a ray arriving from the back (`wi.z <= 0`) scatters nothing.
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/conductor.rs`.
//!
//! The only component is a delta reflection, so `eval` and `pdf` are zero and `sample` returns
//! the mirror direction with probability 1.
use super::fresnel::fresnel_conductor;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Smooth metal with complex Fresnel (`conductor`).
#[derive(Clone, Debug)]
pub struct Conductor {
    /// Real part of the index of refraction (per channel).
    pub eta: Texture,
    /// Imaginary part (absorption coefficient, per channel).
    pub k: Texture,
    /// Tint multiplied into the reflectance.
    pub specular_reflectance: Texture,
}

impl Conductor {
    /// A delta model: always zero.
    pub fn eval(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> Color {
        Color::ZERO
    }
    /// A delta model: always zero.
    pub fn pdf(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> f32 {
        0.0
    }
    /// The mirror direction, with weight `F(cos theta_i) * specular_reflectance`.
    pub fn sample(&self, wi: Vec3, _u1: f32, _u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let f = conductor_fresnel(wi.z, &self.eta, &self.k, at);
        let weight = f * self.specular_reflectance.eval(at);
        Some(BsdfSample::delta(
            Vec3::new(-wi.x, -wi.y, wi.z),
            weight,
            1.0,
        ))
    }
    /// No smooth component.
    pub fn has_smooth(&self) -> bool {
        false
    }
    /// A delta reflection.
    pub fn has_delta(&self) -> bool {
        true
    }
}

/// Conductor Fresnel with textured `eta` and `k`; the perfect reflector (`material` `none`:
/// constant `eta` 0 and `k` 1) skips the complex formula, which gives exactly 1 there for every
/// cosine (checked for all floats in `[0, 1]`; the test below samples them), so no bit changes.
#[inline]
pub(super) fn conductor_fresnel(cos: f32, eta: &Texture, k: &Texture, at: ShadingPoint) -> Color {
    match (eta, k) {
        (Texture::Constant(e), Texture::Constant(k)) if *e == Color::ZERO && *k == Color::ONE => {
            Color::ONE
        }
        _ => fresnel_conductor(cos, eta.eval(at), k.eval(at)),
    }
}

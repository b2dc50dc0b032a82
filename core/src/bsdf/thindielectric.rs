//! A thin glass sheet (Mitsuba 3's `thindielectric`): two parallel interfaces so close that
//! light leaves where it entered. Reflection sums every odd number of internal bounces,
//! `R = F + (1-F)^2 F / (1 - F^2) = 2F / (1 + F)`, and transmission passes straight through
//! (`wo = -wi`, no refraction, `eta` = 1) with `1 - R`. Both sides behave alike.
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/dielectric.rs`.
//!
//! Two delta components chosen with probabilities `R` and `1 - R`; the weights are the tints.
use super::fresnel::fresnel_dielectric;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// A thin glass sheet (`thindielectric`).
#[derive(Clone, Debug)]
pub struct ThinDielectric {
    /// Relative index `int_ior / ext_ior`.
    pub eta: f32,
    /// Tint of the reflection.
    pub specular_reflectance: Texture,
    /// Tint of the transmission.
    pub specular_transmittance: Texture,
}

impl ThinDielectric {
    /// Total reflectance of the sheet at incident cosine `cos` (either side).
    pub fn reflectance(&self, cos: f32) -> f32 {
        let f = fresnel_dielectric(cos.abs(), self.eta).f;
        2.0 * f / (1.0 + f)
    }
    /// A delta model: always zero.
    pub fn eval(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> Color {
        Color::ZERO
    }
    /// A delta model: always zero.
    pub fn pdf(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> f32 {
        0.0
    }
    /// Mirror reflection with probability `R`, else straight through.
    pub fn sample(&self, wi: Vec3, u1: f32, _u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if wi.z == 0.0 || !wi.is_finite() {
            return None;
        }
        let r = self.reflectance(wi.z);
        let (wo, weight, pdf) = if u1 < r {
            (
                Vec3::new(-wi.x, -wi.y, wi.z),
                self.specular_reflectance.eval(at),
                r,
            )
        } else {
            (-wi, self.specular_transmittance.eval(at), 1.0 - r)
        };
        Some(BsdfSample::delta(wo, weight, pdf))
    }
    /// No smooth component.
    pub fn has_smooth(&self) -> bool {
        false
    }
    /// Delta reflection and transmission.
    pub fn has_delta(&self) -> bool {
        true
    }
}

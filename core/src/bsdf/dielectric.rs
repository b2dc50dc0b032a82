//! Smooth glass: a sharp interface between two dielectrics with Fresnel reflection and
//! refraction (Mitsuba 3's `dielectric`). Works from both sides: `wi.z < 0` means the ray
//! arrives from inside.
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/dielectric.rs`.
//!
//! Two delta components: the mirror direction, chosen with probability `F` (the Fresnel
//! reflectance at `cos theta_i`), and the refracted direction with probability `1 - F`
//! (always reflection under total internal reflection). Both weights are the tints; the
//! refraction's also carries the radiance scaling `1 / eta^2` (`eta` = `eta_t / eta_i`).
use super::fresnel::{fresnel_dielectric, refract};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Smooth glass: Fresnel reflection and refraction (`dielectric`).
#[derive(Clone, Debug)]
pub struct Dielectric {
    /// Relative index `int_ior / ext_ior`.
    pub eta: f32,
    /// Tint of the reflection.
    pub specular_reflectance: Texture,
    /// Tint of the refraction.
    pub specular_transmittance: Texture,
}

impl Dielectric {
    /// A delta model: always zero.
    pub fn eval(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> Color {
        Color::ZERO
    }
    /// A delta model: always zero.
    pub fn pdf(&self, _wi: Vec3, _wo: Vec3, _at: ShadingPoint) -> f32 {
        0.0
    }
    /// Reflection with probability `F`, else refraction (`u1` chooses).
    pub fn sample(&self, wi: Vec3, u1: f32, _u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if wi.z == 0.0 || !wi.is_finite() {
            return None;
        }
        let fr = fresnel_dielectric(wi.z, self.eta);
        // `<` rather than `<=`: a component of probability zero is never chosen.
        if u1 < fr.f {
            let weight = self.specular_reflectance.eval(at);
            Some(BsdfSample::delta(
                Vec3::new(-wi.x, -wi.y, wi.z),
                weight,
                fr.f,
            ))
        } else {
            let wo = refract(wi, Vec3::Z, fr.cos_t, fr.eta_ti);
            Some(BsdfSample {
                wo,
                weight: self.specular_transmittance.eval(at) * (fr.eta_ti * fr.eta_ti),
                pdf: 1.0 - fr.f,
                delta: true,
                eta: fr.eta_it,
            })
        }
    }
    /// No smooth component.
    pub fn has_smooth(&self) -> bool {
        false
    }
    /// Delta reflection and refraction.
    pub fn has_delta(&self) -> bool {
        true
    }
}

//! Lambertian reflection, one-sided as in Mitsuba 3 (the back side is black; wrap it in
//! `twosided` for both sides).
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/basic.rs`.
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::INV_PI;
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Lambertian BRDF `reflectance / pi`, sampled by the cosine.
#[derive(Clone, Debug)]
pub struct Diffuse {
    /// Albedo in `[0, 1]` per channel.
    pub reflectance: Texture,
}

impl Diffuse {
    /// `reflectance / pi * cos theta_o` on the front side, else 0.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return Color::ZERO;
        }
        self.reflectance.eval(at) * (INV_PI * wo.z)
    }
    /// Cosine-hemisphere density.
    #[inline]
    pub fn pdf(&self, wi: Vec3, wo: Vec3, _at: ShadingPoint) -> f32 {
        if wi.z <= 0.0 {
            return 0.0;
        }
        cosine_hemisphere_pdf(wo)
    }
    /// Cosine-weighted sample; the weight is the reflectance.
    #[inline]
    pub fn sample(&self, wi: Vec3, _u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if wi.z <= 0.0 {
            return None;
        }
        let wo = square_to_cosine_hemisphere(u2);
        let pdf = cosine_hemisphere_pdf(wo);
        if !(pdf > 0.0) {
            return None;
        }
        Some(BsdfSample {
            wo,
            weight: self.reflectance.eval(at),
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}

impl Diffuse {
    /// Always smooth.
    #[inline]
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// Never delta.
    #[inline]
    pub fn has_delta(&self) -> bool {
        false
    }
}

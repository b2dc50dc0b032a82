//! Chalmers' tinted Blinn-Phong metal (`blinnphong_metal`), from the Chalmers path-tracer
//! tutorial (task 4).
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/chalmers.rs`.
//!
//! `f = color F D G / (4 (n.wi)(n.wo))` with the terms of [`BlinnPhong`](super::blinnphong::BlinnPhong)'s
//! lobe; the refracted share `1 - F` is absorbed (the tutorial's `refraction_brdf` of a metal
//! is zero). One-sided. Sampling always draws the lobe (the tutorial's 50% choice of the
//! absorbing "refraction" would only waste samples; the pdf is the lobe's exactly).
use super::blinnphong::Lobe;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Chalmers' tinted Blinn-Phong metal (`blinnphong_metal`).
#[derive(Clone, Debug)]
pub struct BlinnPhongMetal {
    pub(super) color: Texture,
    lobe: Lobe,
}

impl BlinnPhongMetal {
    /// A metal tinted by `color`, exponent `shininess >= 0`, Schlick `r0` in `[0, 1]`.
    pub fn new(color: Texture, shininess: f32, r0: f32) -> Self {
        BlinnPhongMetal {
            color,
            lobe: Lobe { shininess, r0 },
        }
    }

    /// `f(wi, wo) |cos theta_o|`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let v = self.lobe.eval(wi, wo);
        if v > 0.0 {
            self.color.eval(at) * v
        } else {
            Color::ZERO
        }
    }
    /// Density of the lobe.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, _at: ShadingPoint) -> f32 {
        self.lobe.pdf(wi, wo)
    }
    /// Samples the lobe.
    pub fn sample(&self, wi: Vec3, _u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        let wo = self.lobe.sample(wi, u2)?;
        let pdf = self.lobe.pdf(wi, wo);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        Some(BsdfSample {
            wo,
            weight: self.color.eval(at) * (self.lobe.eval(wi, wo) / pdf),
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
    /// Always smooth.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// Never delta.
    pub fn has_delta(&self) -> bool {
        false
    }
}

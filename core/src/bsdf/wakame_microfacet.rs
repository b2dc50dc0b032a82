//! Wakame's (Nori's) `microfacet`: a Beckmann rough dielectric reflection over a Lambertian
//! base, one-sided (the back side is black).
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/wakame.rs`.
//!
//! Model (the assignment's formula): `f = kd / pi + ks D(h) F(h.wi) G1(wi, h) G1(wo, h) /
//! (4 cos theta_i cos theta_o)` with `ks = 1 - max(kd)`, Beckmann `D`, dielectric Fresnel `F`
//! and the rational Smith approximation. Sampling picks the specular lobe with probability `ks`
//! (a half vector by `D(h) cos theta_h`, reflected) and the cosine lobe otherwise, so
//! `pdf = ks D(h) cos theta_h / (4 h.wo) + (1 - ks) cos theta_o / pi`.
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetKind};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::{Norm, INV_PI};
use crate::sampling::warp::cosine_hemisphere_pdf;
use crate::Color;
use glam::{Vec2, Vec3};

/// Beckmann microfacet reflection over diffuse.
#[derive(Clone, Debug)]
pub struct WakameMicrofacet {
    distr: Microfacet,
    eta: f32,
    kd: Color,
    ks: f32,
}

impl WakameMicrofacet {
    /// The model for roughness `alpha` (> 0), relative index `eta = int_ior / ext_ior` (> 0)
    /// and diffuse reflectance `kd` in `[0, 1]`.
    pub fn new(alpha: f32, eta: f32, kd: Color) -> Self {
        WakameMicrofacet {
            distr: Microfacet {
                kind: MicrofacetKind::Beckmann,
                alpha_u: alpha,
                alpha_v: alpha,
                sample_visible: false,
            },
            eta,
            kd,
            ks: (1.0 - kd.max_element()).clamp(0.0, 1.0),
        }
    }

    /// The specular weight `ks = 1 - max(kd)`.
    pub fn ks(&self) -> f32 {
        self.ks
    }

    /// `f(wi, wo) cos theta_o` on the front side.
    pub fn eval(&self, wi: Vec3, wo: Vec3, _at: ShadingPoint) -> Color {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return Color::ZERO;
        }
        let h = (wi + wo).unit();
        let spec =
            self.distr.d(h) * fresnel_dielectric(h.dot(wi), self.eta).f * self.distr.g(wi, wo, h)
                / (4.0 * wi.z * wo.z);
        let f = self.kd * INV_PI + Color::splat(self.ks * spec);
        let r = f * wo.z;
        if r.is_finite() {
            r
        } else {
            Color::ZERO
        }
    }

    /// `ks D(h) cos theta_h / (4 h.wo) + (1 - ks) cos theta_o / pi` on the front side.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, _at: ShadingPoint) -> f32 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return 0.0;
        }
        let h = (wi + wo).unit();
        let spec = self.distr.d(h) * h.z / (4.0 * h.dot(wo));
        let p = self.ks * spec + (1.0 - self.ks) * cosine_hemisphere_pdf(wo);
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }

    /// `u1 < ks` samples the specular lobe, otherwise the cosine lobe.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let wo = self.distr.sample_glossy_or_diffuse(wi, u1, u2, self.ks)?;
        BsdfSample::smooth_reflection(wo, self.eval(wi, wo, at), self.pdf(wi, wo, at))
    }

    /// Both lobes are smooth.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// No delta lobe.
    pub fn has_delta(&self) -> bool {
        false
    }
}

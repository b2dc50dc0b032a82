//! Polarized plastic (Mitsuba 3's `pplastic`) as Mitsuba 3's unpolarized (RGB) variants
//! evaluate it: a rough dielectric reflection added to a diffuse term attenuated by two smooth
//! refractions, without the coupling of `plastic` / `roughplastic`. One-sided (the back side
//! is black). Tessera renders unpolarized light, so the Mueller matrices of Mitsuba's
//! polarized variants reduce to their intensity terms, which are these.
//!
//! Its scene parameters are declared with its loader, in `scene/src/materials/polarized.rs`.
//!
//! Model: `f cos = s F(wi.h) D(h) G(wi, wo, h) / (4 cos theta_i)` (microfacet reflection,
//! Beckmann or GGX, possibly anisotropic) plus `d (1 - F(cos theta_i)) (1 - F(cos theta_o))
//! cos theta_o / pi`, `F` the dielectric Fresnel reflectance of relative index `eta`. Unlike
//! `roughplastic` the diffuse term has no `1 / eta^2` and no internal-reflection factor, and
//! the specular lobe is chosen with the fixed probability `w = s_mean / (d_mean + s_mean)` of
//! the textures' means (no Fresnel-dependent weighting). Roughness below 1e-4 acts as 1e-4.
use super::fresnel::fresnel_dielectric;
use super::microfacet::Microfacet;
use super::plastic_common::specular_sampling_weight;
use super::roughness_texture::{distribution_at, RoughnessTexture};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::{Norm, INV_PI};
use crate::sampling::warp::cosine_hemisphere_pdf;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Polarized plastic (`pplastic`) seen through unpolarized light.
#[derive(Clone, Debug)]
pub struct PolarizedPlastic {
    /// Albedo of the diffuse term.
    pub diffuse: Texture,
    /// Factor on the specular reflection.
    pub specular: Texture,
    /// Relative index `int / ext` (read as a scalar; must be positive to reflect anything).
    pub eta: Texture,
    distr: Microfacet,
    pub(super) roughness: Option<RoughnessTexture>,
    spec_weight: f32,
}

impl PolarizedPlastic {
    /// A polarized plastic with diffuse albedo `diffuse`, specular factor `specular`, relative
    /// index `eta`, distribution `distr` (its roughness raised to at least 1e-4) and, when
    /// given, roughness textures that replace `distr`'s values. The specular sampling weight
    /// is computed from the two textures' means.
    pub fn new(
        diffuse: Texture,
        specular: Texture,
        eta: Texture,
        distr: Microfacet,
        roughness: Option<RoughnessTexture>,
    ) -> Self {
        let spec_weight = specular_sampling_weight(&diffuse, &specular);
        PolarizedPlastic {
            diffuse,
            specular,
            eta,
            distr: Microfacet {
                alpha_u: distr.alpha_u.max(1e-4),
                alpha_v: distr.alpha_v.max(1e-4),
                ..distr
            },
            roughness,
            spec_weight,
        }
    }

    /// Probability of sampling the specular lobe.
    pub fn specular_sampling_weight(&self) -> f32 {
        self.spec_weight
    }

    fn eta_at(&self, at: ShadingPoint) -> Option<f32> {
        let e = self.eta.eval_1(at);
        (e.is_finite() && e > 0.0).then_some(e)
    }

    /// `f(wi, wo) cos theta_o`: specular plus diffuse, front side only.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return Color::ZERO;
        }
        let Some(eta) = self.eta_at(at) else {
            return Color::ZERO;
        };
        let md = distribution_at(&self.distr, &self.roughness, at);
        let h = (wi + wo).unit();
        let f = fresnel_dielectric(wi.dot(h), eta).f;
        let spec = md.d(h) * md.g(wi, wo, h) * f / (4.0 * wi.z);
        let ti = 1.0 - fresnel_dielectric(wi.z, eta).f;
        let to = 1.0 - fresnel_dielectric(wo.z, eta).f;
        let r = self.specular.eval(at) * spec + self.diffuse.eval(at) * (ti * to * wo.z * INV_PI);
        if r.is_finite() {
            r
        } else {
            Color::ZERO
        }
    }

    /// `w p_spec + (1 - w) cos theta_o / pi`, `p_spec` the density of mirroring `wi` about a
    /// sampled microfacet normal.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return 0.0;
        }
        let md = distribution_at(&self.distr, &self.roughness, at);
        let h = (wi + wo).unit();
        let spec = if wi.dot(h) <= 0.0 || wo.dot(h) <= 0.0 {
            0.0
        } else {
            md.reflected_pdf(wi, wo, h)
        };
        let w = self.spec_weight;
        let p = w * spec + (1.0 - w) * cosine_hemisphere_pdf(wo);
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }

    /// `u1 < w` mirrors `wi` about a sampled microfacet normal, else a cosine-weighted
    /// direction; the weight is `eval / pdf` of the whole mixture.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let md = distribution_at(&self.distr, &self.roughness, at);
        let wo = md.sample_glossy_or_diffuse(wi, u1, u2, self.spec_weight)?;
        BsdfSample::smooth_reflection(wo, self.eval(wi, wo, at), self.pdf(wi, wo, at))
    }

    /// Both terms are smooth.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// No delta component.
    pub fn has_delta(&self) -> bool {
        false
    }
}

//! Rough glass: microfacet reflection and refraction at a rough interface between two
//! dielectrics (Walter et al. 2007, "Microfacet Models for Refraction through Rough
//! Surfaces"; Mitsuba 3's `roughdielectric`). Works from both sides: `wi.z < 0` means the ray
//! arrives from inside.
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/dielectric.rs`.
//!
//! # Model
//!
//! With `eta` the index on the side of `wo` over the index on the side of `wi`, the half
//! vector is `m = normalize(wi + wo)` for reflection and `m = normalize(wi + eta wo)` for
//! refraction, flipped into the upper hemisphere. Then
//! - reflection: `f cos_o = F D G / (4 |cos_i|)`;
//! - refraction: `f cos_o = (1-F) D G |wi.m| |wo.m| / (|cos_i| (wi.m + eta wo.m)^2)`, which is
//!   Walter's expression times the radiance scaling `1 / eta^2`;
//!
//! with `F` the dielectric Fresnel reflectance at `wi.m` and `G = G1(wi, m) G1(wo, m)`. Pairs
//! whose microfacet and macro-surface disagree on a side are zero.
//!
//! # Sampling
//!
//! A normal `m` is drawn for `wi` mirrored into the upper hemisphere; reflection is chosen with
//! probability `F(wi.m)`, otherwise refraction through `m`. The density is `pdf_m(m)` times the
//! choice probability times the Jacobian of the half-vector map, `1 / (4 |wo.m|)` or
//! `eta^2 |wo.m| / (wi.m + eta wo.m)^2`. Without visible-normal sampling the roughness of the
//! sampled distribution is widened by `1.2 - 0.2 sqrt(|cos_i|)` (Walter's trick, as Mitsuba 3
//! does); the weight then carries the ratio of the two densities, so it stays `f cos / pdf`.
use super::fresnel::{fresnel_dielectric, reflect, refract};
use super::microfacet::Microfacet;
use super::roughness_texture::{distribution_at, RoughnessTexture};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::{sqrt, Norm};
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Rough glass, Walter et al. 2007 (`roughdielectric`).
#[derive(Clone, Debug)]
pub struct RoughDielectric {
    /// Normal distribution, roughness and sampling strategy.
    pub distribution: Microfacet,
    /// Roughness read from textures instead of `distribution`'s, when given as textures.
    pub roughness: Option<RoughnessTexture>,
    /// Relative index `int_ior / ext_ior` (not 1).
    pub eta: f32,
    /// Tint of the reflection.
    pub specular_reflectance: Texture,
    /// Tint of the refraction.
    pub specular_transmittance: Texture,
}

/// The microfacet configuration of a pair of directions.
struct Pair {
    /// Half vector (upper hemisphere).
    m: Vec3,
    /// Same side (reflection) or opposite sides (refraction).
    reflect: bool,
    /// Index on the side of `wo` over the index on the side of `wi`, for refraction.
    eta: f32,
    /// `wi.m` and `wo.m`.
    cos_im: f32,
    cos_om: f32,
}

impl Pair {
    /// Jacobian `|d m / d wo|` of the half-vector map.
    #[inline]
    fn jacobian(&self) -> f32 {
        if self.reflect {
            1.0 / (4.0 * self.cos_om.abs())
        } else {
            let den = self.cos_im + self.eta * self.cos_om;
            self.eta * self.eta * self.cos_om.abs() / (den * den)
        }
    }
}

impl RoughDielectric {
    /// The half vector and side of `(wi, wo)`, or `None` for grazing or inconsistent pairs.
    fn pair(&self, wi: Vec3, wo: Vec3) -> Option<Pair> {
        let (ci, co) = (wi.z, wo.z);
        if ci == 0.0 || co == 0.0 || !(wi.is_finite() && wo.is_finite()) {
            return None;
        }
        let reflect = ci * co > 0.0;
        let eta = if ci > 0.0 { self.eta } else { 1.0 / self.eta };
        let mut m = (wi + wo * if reflect { 1.0 } else { eta }).unit();
        if !m.is_finite() {
            return None;
        }
        if m.z < 0.0 {
            m = -m;
        }
        let (cos_im, cos_om) = (wi.dot(m), wo.dot(m));
        (cos_im * ci > 0.0 && cos_om * co > 0.0).then_some(Pair {
            m,
            reflect,
            eta,
            cos_im,
            cos_om,
        })
    }

    /// The distribution normals are drawn from at incident cosine `cos_i`.
    fn sampling_distribution(md: &Microfacet, cos_i: f32) -> Microfacet {
        let mut d = *md;
        if !d.sample_visible {
            let s = 1.2 - 0.2 * sqrt(cos_i.abs());
            d.alpha_u *= s;
            d.alpha_v *= s;
        }
        d
    }

    /// `f(wi, wo) |cos theta_o|`, reflection or refraction by the sides of `wi` and `wo`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let Some(p) = self.pair(wi, wo) else {
            return Color::ZERO;
        };
        let md = &distribution_at(&self.distribution, &self.roughness, at);
        let d = md.d(p.m);
        if d == 0.0 {
            return Color::ZERO;
        }
        let f = fresnel_dielectric(p.cos_im, self.eta).f;
        let g = md.g(wi, wo, p.m);
        if p.reflect {
            self.specular_reflectance.eval(at) * (f * d * g / (4.0 * wi.z.abs()))
        } else {
            let den = p.cos_im + p.eta * p.cos_om;
            let v = (1.0 - f) * d * g * (p.cos_im * p.cos_om).abs() / (wi.z.abs() * den * den);
            self.specular_transmittance.eval(at) * v
        }
    }

    /// Density of `sample` at `wo`.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let Some(p) = self.pair(wi, wo) else {
            return 0.0;
        };
        let md = distribution_at(&self.distribution, &self.roughness, at);
        let sd = Self::sampling_distribution(&md, wi.z);
        let wi_up = if wi.z > 0.0 { wi } else { -wi };
        let f = fresnel_dielectric(p.cos_im, self.eta).f;
        let choice = if p.reflect { f } else { 1.0 - f };
        sd.pdf(wi_up, p.m) * choice * p.jacobian()
    }

    /// Draws a normal, then reflects (probability `F`) or refracts through it.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        let ci = wi.z;
        if ci == 0.0 || !wi.is_finite() {
            return None;
        }
        let md = &distribution_at(&self.distribution, &self.roughness, at);
        let sd = Self::sampling_distribution(md, ci);
        let wi_up = if ci > 0.0 { wi } else { -wi };
        let (m, pdf_m) = sd.sample(wi_up, u2)?;
        let cos_im = wi.dot(m);
        if !(cos_im * ci > 0.0) {
            return None;
        }
        let fr = fresnel_dielectric(cos_im, self.eta);
        let (wo, pdf, tint, eta) = if u1 < fr.f {
            let wo = reflect(wi, m);
            if !(wo.z * ci > 0.0) {
                return None;
            }
            let pdf = pdf_m * fr.f / (4.0 * cos_im.abs());
            (wo, pdf, self.specular_reflectance.eval(at), 1.0)
        } else {
            let wo = refract(wi, m, fr.cos_t, fr.eta_ti);
            if !(wo.z * ci < 0.0) {
                return None;
            }
            let e = fr.eta_it;
            let den = cos_im + e * wo.dot(m);
            let pdf = pdf_m * (1.0 - fr.f) * e * e * wo.dot(m).abs() / (den * den);
            let scale = fr.eta_ti * fr.eta_ti;
            (wo, pdf, self.specular_transmittance.eval(at) * scale, e)
        };
        // f cos / pdf in closed form: the Fresnel choice and the Jacobian cancel.
        let g = if md.sample_visible {
            md.g1(wo, m)
        } else {
            md.d(m) / sd.d(m) * md.g(wi, wo, m) * cos_im.abs() / (ci.abs() * m.z)
        };
        (pdf.is_finite() && pdf > 0.0 && g > 0.0 && g.is_finite()).then_some(BsdfSample {
            wo: wo.unit(),
            weight: tint * g,
            pdf,
            delta: false,
            eta,
        })
    }
    /// Glossy reflection and refraction.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// No delta component.
    pub fn has_delta(&self) -> bool {
        false
    }
}

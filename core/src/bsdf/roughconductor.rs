//! Rough metal: a Torrance-Sparrow microfacet reflection model with conductor Fresnel (Mitsuba
//! 3's `roughconductor`). One-sided: nothing scatters when `wi` or `wo` is below the surface.
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/conductor.rs`.
//!
//! `f(wi, wo) = F(wi.h) D(h) G(wi, wo, h) / (4 cos theta_i cos theta_o)` with the half vector
//! `h = normalize(wi + wo)`. Sampling draws a microfacet normal `m` (visible normals by
//! default) and reflects `wi` about it; the density of `wo` is `pdf_m(m) / (4 wo.m)`.
use super::conductor::conductor_fresnel;
use super::fresnel::reflect;
use super::microfacet::Microfacet;
use super::roughness_texture::{distribution_at, RoughnessTexture};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::Norm;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Rough metal, microfacet (`roughconductor`).
#[derive(Clone, Debug)]
pub struct RoughConductor {
    /// Normal distribution, roughness and sampling strategy.
    pub distribution: Microfacet,
    /// Roughness read from textures instead of `distribution`'s, when given as textures.
    pub roughness: Option<RoughnessTexture>,
    /// Real part of the index of refraction (per channel).
    pub eta: Texture,
    /// Imaginary part (per channel).
    pub k: Texture,
    /// Tint multiplied into the reflectance.
    pub specular_reflectance: Texture,
}

impl RoughConductor {
    /// The half vector of a front-side pair, or `None` when the micro- and macro-surface
    /// disagree on the side (or the pair is degenerate).
    #[inline]
    fn half_vector(wi: Vec3, wo: Vec3) -> Option<Vec3> {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return None;
        }
        let h = (wi + wo).unit();
        (h.is_finite() && wi.dot(h) > 0.0 && wo.dot(h) > 0.0).then_some(h)
    }

    #[inline]
    fn fresnel(&self, cos: f32, at: ShadingPoint) -> Color {
        conductor_fresnel(cos, &self.eta, &self.k, at) * self.specular_reflectance.eval(at)
    }

    /// The shape of the lobe toward `wo`, `D(h) / (4 cos theta_i)`: [`RoughConductor::eval`]
    /// without the Fresnel factor, the tint and the masking term (all near constant over the
    /// lobe), for weighing lights against each other at a vertex. No texture lookup.
    #[inline]
    pub fn lobe(&self, wi: Vec3, wo: Vec3) -> f32 {
        match Self::half_vector(wi, wo) {
            Some(h) => self.distribution.d(h) / (4.0 * wi.z),
            None => 0.0,
        }
    }

    /// `f(wi, wo) cos theta_o`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let Some(h) = Self::half_vector(wi, wo) else {
            return Color::ZERO;
        };
        let md = &distribution_at(&self.distribution, &self.roughness, at);
        let d = md.d(h);
        if d == 0.0 {
            return Color::ZERO;
        }
        let g = md.g(wi, wo, h);
        self.fresnel(wi.dot(h), at) * (d * g / (4.0 * wi.z))
    }

    /// Density of `sample`: the normal's density times the reflection Jacobian `1 / (4 wo.h)`.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let Some(h) = Self::half_vector(wi, wo) else {
            return 0.0;
        };
        distribution_at(&self.distribution, &self.roughness, at).pdf(wi, h) / (4.0 * wo.dot(h))
    }

    /// Reflects `wi` about a sampled microfacet normal.
    pub fn sample(&self, wi: Vec3, _u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let md = &distribution_at(&self.distribution, &self.roughness, at);
        let (m, pdf_m) = md.sample(wi, u2)?;
        let cos_im = wi.dot(m);
        let wo = reflect(wi, m);
        if !(cos_im > 0.0 && wo.z > 0.0) {
            return None;
        }
        let pdf = pdf_m / (4.0 * cos_im);
        // f cos / pdf in closed form: D cancels (and G1(wi) too for visible normals).
        let g = if md.sample_visible {
            md.g1(wo, m)
        } else {
            md.g(wi, wo, m) * cos_im / (wi.z * m.z)
        };
        let weight = self.fresnel(cos_im, at) * g;
        (pdf.is_finite() && pdf > 0.0 && g > 0.0).then_some(BsdfSample {
            wo: wo.unit(),
            weight,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
    /// A glossy reflection.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// No delta component.
    pub fn has_delta(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::microfacet::MicrofacetKind;

    /// For the perfect reflector (Fresnel 1, no tint), `eval` is the lobe times the masking
    /// term, and both vanish together on the wrong side.
    #[test]
    fn lobe_is_eval_without_fresnel_and_masking() {
        for kind in [MicrofacetKind::Beckmann, MicrofacetKind::Ggx] {
            let c = RoughConductor {
                distribution: Microfacet::new(kind, 0.3),
                eta: Texture::Constant(Color::ZERO),
                k: Texture::Constant(Color::ONE),
                specular_reflectance: Texture::Constant(Color::ONE),
                roughness: None,
            };
            let wi = Vec3::new(0.3, -0.2, 0.9).unit();
            for wo in [
                Vec3::new(-0.3, 0.2, 0.9).unit(),
                Vec3::new(0.5, 0.5, 0.4).unit(),
                Vec3::new(-0.8, 0.1, 0.2).unit(),
            ] {
                let h = (wi + wo).unit();
                let g = c.distribution.g(wi, wo, h);
                let f = c.eval(wi, wo, Vec2::ZERO.into());
                let want = c.lobe(wi, wo) * g;
                assert!(
                    (f.x - want).abs() <= 1e-5 * want,
                    "{kind:?} {wo}: {f} {want}"
                );
                assert!(c.lobe(wi, wo) > 0.0);
            }
            assert_eq!(c.lobe(wi, Vec3::new(0.0, 0.6, -0.8)), 0.0);
        }
    }
}

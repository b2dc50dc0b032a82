//! Rough plastic (Mitsuba 3's `roughplastic`): a rough dielectric coating (microfacet
//! reflection, Walter et al. 2007) over a diffuse base, one-sided (the back side is black).
//!
//! Roughness values below 1e-4 act as 1e-4, as in Mitsuba 3. Its scene parameters are declared with
//! its loader, in `scene/src/materials/plastic.rs`.
//!
//! Model (as Mitsuba 3): `f cos = s F(wi.h) D(h) G(wi, wo, h) / (4 cos theta_i)` for the coating
//! plus `d' / pi / eta^2 cos theta_o T(cos theta_i) T(cos theta_o)` for the base, where `T` is the
//! coating's tabulated external transmittance and `d' = d / (1 - R_int)` (or `d / (1 - d R_int)`
//! with `nonlinear`), `R_int` the coating's internal diffuse reflectance; both are computed when
//! the material is built ([`super::plastic_common::rough_tables`]). The coating is chosen with
//! probability proportional to `(1 - T(cos theta_i)) w` against `T(cos theta_i) (1 - w)`.
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetKind};
use super::plastic_common::{
    coating_probability, internal_scattering, lerp_table, rough_tables, specular_sampling_weight,
    TABLE_RES,
};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::{Norm, INV_PI};
use crate::sampling::warp::cosine_hemisphere_pdf;
use crate::texture::Texture;
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// Rough coating over a diffuse base.
#[derive(Clone, Debug)]
pub struct RoughPlastic {
    pub(super) diffuse: Texture,
    pub(super) specular: Texture,
    distr: Microfacet,
    eta: f32,
    nonlinear: bool,
    inv_eta_2: f32,
    spec_weight: f32,
    transmittance: Box<[f32; TABLE_RES]>,
    internal_reflectance: f32,
}

impl RoughPlastic {
    /// A rough plastic with the given base albedo, coating factor, distribution `kind`,
    /// roughness `alpha` (> 0; at least 1e-4 is used), visible-normal sampling switch, relative
    /// index `eta = int_ior / ext_ior` (> 0, != 1) and `nonlinear` switch. Integrates the
    /// coating's tables (a few hundred thousand microfacet samples).
    pub fn new(
        diffuse: Texture,
        specular: Texture,
        kind: MicrofacetKind,
        alpha: f32,
        sample_visible: bool,
        eta: f32,
        nonlinear: bool,
    ) -> Self {
        let alpha = alpha.max(1e-4);
        let (transmittance, internal_reflectance) = rough_tables(kind, alpha, eta);
        let spec_weight = specular_sampling_weight(&diffuse, &specular);
        RoughPlastic {
            diffuse,
            specular,
            distr: Microfacet {
                kind,
                alpha_u: alpha,
                alpha_v: alpha,
                sample_visible,
            },
            eta,
            nonlinear,
            inv_eta_2: 1.0 / (eta * eta),
            spec_weight,
            transmittance,
            internal_reflectance,
        }
    }

    /// The coating's internal diffuse reflectance `R_int`.
    pub fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }

    /// The coating's external transmittance for incident cosine `mu` (interpolated).
    pub fn transmittance(&self, mu: f32) -> f32 {
        lerp_table(&self.transmittance, mu)
    }

    /// `f(wi, wo) cos theta_o`: coating plus base, front side only.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return Color::ZERO;
        }
        let h = (wi + wo).unit();
        let d = self.distr.d(h);
        let f = fresnel_dielectric(wi.dot(h), self.eta).f;
        let g = self.distr.g(wi, wo, h);
        let spec = self.specular.eval(at) * (f * d * g / (4.0 * wi.z));
        let (ti, to) = (self.transmittance(wi.z), self.transmittance(wo.z));
        let base = internal_scattering(
            self.diffuse.eval(at),
            self.internal_reflectance,
            self.nonlinear,
        );
        let r = spec + base * (INV_PI * self.inv_eta_2 * wo.z * ti * to);
        if r.is_finite() {
            r
        } else {
            Color::ZERO
        }
    }

    /// Mixture of the microfacet reflection density and the cosine density, weighted by the
    /// component probabilities.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, _at: ShadingPoint) -> f32 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return 0.0;
        }
        let Some(ps) = coating_probability(1.0 - self.transmittance(wi.z), self.spec_weight) else {
            return 0.0;
        };
        let h = (wi + wo).unit();
        let spec = self.distr.reflected_pdf(wi, wo, h);
        let p = ps * spec + (1.0 - ps) * cosine_hemisphere_pdf(wo);
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }

    /// `u1` chooses the coating (a microfacet normal, then the mirror direction about it) or
    /// the base (cosine); the weight is `eval / pdf` of the whole mixture.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let ps = coating_probability(1.0 - self.transmittance(wi.z), self.spec_weight)?;
        let wo = self.distr.sample_glossy_or_diffuse(wi, u1, u2, ps)?;
        BsdfSample::smooth_reflection(wo, self.eval(wi, wo, at), self.pdf(wi, wo, at))
    }

    /// Both components are smooth.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// No delta component.
    pub fn has_delta(&self) -> bool {
        false
    }
}

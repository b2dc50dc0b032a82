//! Mitsuba 3's `principledthin` BSDF: Burley's thin-surface variant of the Disney model
//! ("Extending the Disney BRDF to a BSDF with Integrated Subsurface Scattering", 2015) as
//! Mitsuba 3.9.1 writes it, for sheets without volume (leaves, paper, cloth, thin glass).
//!
//! The surface is symmetric: both sides behave as the front, `wi` and `wo` mirrored together.
//! Lobes (`t` spec_trans, `d` = diff_trans / 2):
//! - microfacet reflection `t F_thin D G / (4 cos_i)`, GGX of `roughness^2` (stretched by
//!   `anisotropic`), `F_thin` the dielectric Fresnel of `eta` blended by `spec_tint` toward a
//!   Schlick term of the base colour's hue;
//! - thin transmission: the same reflection mirrored through the sheet (no bending), with
//!   roughness scaled by `0.65 eta - 0.35`, `t base_color (1 - F) D G / (4 cos_i)`;
//! - Burley's diffuse with retro-reflection, flatness and sheen, weighted `(1 - t)(1 - d)`;
//! - Lambertian transmission `(1 - t) d base_color / pi`.
//!
//! `u1` chooses a lobe with probabilities proportional to `t rate_sr / 2`, `t rate_st / 2`,
//! `rate_dr (1 - t)(1 - d)` and `rate_dt (1 - t) d`. A lobe whose parameter the file does not
//! give (or gives as the float 0) is off, as in Mitsuba. Its scene parameters are declared with
//! its loader, in `scene/src/materials/principled_thin.rs`.
use super::fresnel::{fresnel_dielectric, reflect};
use super::microfacet::{Microfacet, MicrofacetKind};
use super::principled_lobes::{
    burley_diffuse, hue, lerp, main_alphas, micro_compatible, mulsign, schlick_fresnel, schlick_r0,
    sheen_color,
};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::{Norm, INV_PI};
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::texture::Texture;
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// How often each lobe is sampled, relative to its weight (Mitsuba's `*_sampling_rate`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinSamplingRates {
    /// `specular_reflectance_sampling_rate`.
    pub spec_reflect: f32,
    /// `specular_transmittance_sampling_rate`.
    pub spec_trans: f32,
    /// `diffuse_reflectance_sampling_rate`.
    pub diffuse_reflect: f32,
    /// `diffuse_transmittance_sampling_rate`.
    pub diffuse_trans: f32,
}

/// The parameters of a [`PrincipledThin`], as the scene gives them. A lobe's `Option` is
/// `None` when the lobe is off.
#[derive(Clone, Debug)]
pub struct PrincipledThinParams {
    /// Base colour.
    pub base_color: Texture,
    /// Roughness of the specular lobes (scalar).
    pub roughness: Texture,
    /// Anisotropy (scalar).
    pub anisotropic: Option<Texture>,
    /// Weight of the specular lobes (scalar).
    pub spec_trans: Option<Texture>,
    /// Tint of the specular reflection toward the base colour's hue (scalar).
    pub spec_tint: Option<Texture>,
    /// Sheen weight (scalar).
    pub sheen: Option<Texture>,
    /// Tint of the sheen toward the base colour's hue (scalar).
    pub sheen_tint: Option<Texture>,
    /// Blend of the diffuse toward the flattened subsurface approximation (scalar).
    pub flatness: Option<Texture>,
    /// Diffuse transmission, in `[0, 2]` (scalar).
    pub diff_trans: Option<Texture>,
    /// Index of refraction of the sheet (scalar).
    pub eta: Texture,
    /// Lobe sampling rates.
    pub rates: ThinSamplingRates,
}

/// Mitsuba 3's thin principled BSDF.
#[derive(Clone, Debug)]
pub struct PrincipledThin {
    /// Boxed: ten textures would make every `Bsdf` as large.
    pub(super) p: Box<PrincipledThinParams>,
}

/// The scalar parameters at one surface point.
struct ThinWeights {
    roughness: f32,
    anisotropic: Option<f32>,
    spec_trans: f32,
    diff_trans: f32,
    eta: f32,
}

impl ThinWeights {
    /// The reflection's GGX distribution.
    fn reflection(&self) -> Microfacet {
        ggx(main_alphas(self.roughness, self.anisotropic))
    }
    /// The transmission's, its roughness scaled by `0.65 eta - 0.35`.
    fn transmission(&self) -> Microfacet {
        let r = (0.65 * self.eta - 0.35) * self.roughness;
        ggx(main_alphas(r, self.anisotropic))
    }
}

fn ggx((alpha_u, alpha_v): (f32, f32)) -> Microfacet {
    Microfacet {
        kind: MicrofacetKind::Ggx,
        alpha_u,
        alpha_v,
        sample_visible: true,
    }
}

/// `wo` mirrored to the upper side (`|z|`): the direction whose half vector with `wi` is the
/// micro normal of both specular lobes.
fn upper(wo: Vec3) -> Vec3 {
    Vec3::new(wo.x, wo.y, wo.z.abs())
}

impl PrincipledThin {
    /// The model for `p`.
    pub fn new(p: PrincipledThinParams) -> Self {
        PrincipledThin { p: Box::new(p) }
    }

    fn weights(&self, at: ShadingPoint) -> ThinWeights {
        let opt = |t: &Option<Texture>| t.as_ref().map(|t| t.eval_1(at));
        ThinWeights {
            roughness: self.p.roughness.eval_1(at),
            anisotropic: opt(&self.p.anisotropic),
            spec_trans: opt(&self.p.spec_trans).unwrap_or(0.0),
            diff_trans: opt(&self.p.diff_trans).map_or(0.0, |d| d / 2.0),
            eta: self.p.eta.eval_1(at),
        }
    }

    /// The lobe probabilities (specular reflection, specular transmission, diffuse
    /// reflection, diffuse transmission), normalised; `None` unless they sum to a positive
    /// number.
    fn probabilities(&self, w: &ThinWeights) -> Option<[f32; 4]> {
        let r = &self.p.rates;
        let (t, d) = (w.spec_trans, w.diff_trans);
        let has_st = self.p.spec_trans.is_some();
        let p = [
            if has_st {
                t * r.spec_reflect / 2.0
            } else {
                0.0
            },
            if has_st { t * r.spec_trans / 2.0 } else { 0.0 },
            r.diffuse_reflect * (1.0 - t) * (1.0 - d),
            if self.p.diff_trans.is_some() {
                r.diffuse_trans * (1.0 - t) * d
            } else {
                0.0
            },
        ];
        let total: f32 = p.iter().sum();
        (total > 0.0 && total.is_finite()).then(|| p.map(|x| x / total))
    }

    /// `f(wi, wo) |cos theta_o|`: reflection on `wi`'s side, transmission through the sheet.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let r = self.eval_lobes(wi, wo, at);
        if r.is_finite() {
            r
        } else {
            Color::ZERO
        }
    }

    fn eval_lobes(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        if wi.z == 0.0 || !(wi.z * wo.z != 0.0) {
            return Color::ZERO;
        }
        let w = self.weights(at);
        let base = self.p.base_color.eval(at);
        let (wi, wo) = (mulsign(wi, wi.z), mulsign(wo, wi.z));
        let (ci, co) = (wi.z, wo.z);
        let reflect = co > 0.0;
        let wh = (wi + upper(wo)).unit();
        let (t, d) = (w.spec_trans, w.diff_trans);
        let mut value = Color::ZERO;
        if self.p.spec_trans.is_some() && t > 0.0 {
            let f = fresnel_dielectric(wi.dot(wh), w.eta).f;
            if reflect && micro_compatible(wh, wi, wo, ci, true) {
                let distr = w.reflection();
                let tint = self.p.spec_tint.as_ref().map(|s| s.eval_1(at));
                let f_thin = thin_fresnel(f, tint, base, wi.dot(wh), w.eta);
                value += f_thin * (t * distr.d(wh) * distr.g(wi, wo, wh) / (4.0 * ci));
            }
            if !reflect && micro_compatible(wh, wi, wo, ci, false) {
                let distr = w.transmission();
                let s = t * (1.0 - f) * distr.d(wh) * distr.g(wi, wo, wh) / (4.0 * ci);
                value += base * s;
            }
        }
        if reflect && t < 1.0 && d < 1.0 {
            let cos_d = wh.dot(wo);
            let flatness = self.p.flatness.as_ref().map(|f| f.eval_1(at));
            let shape = burley_diffuse(w.roughness, flatness, ci, co, cos_d);
            value += base * ((1.0 - t) * co * INV_PI * (1.0 - d) * shape);
            if let Some(sheen) = &self.p.sheen {
                let tint = self.p.sheen_tint.as_ref().map(|s| s.eval_1(at));
                let s = sheen.eval_1(at) * (1.0 - t) * (1.0 - d) * co;
                value += sheen_color(tint, base, cos_d) * s;
            }
        }
        if !reflect && self.p.diff_trans.is_some() && t < 1.0 && d > 0.0 {
            value += base * ((1.0 - t) * d * INV_PI * co.abs());
        }
        value
    }

    /// Solid-angle density with which [`PrincipledThin::sample`] produces `wo`.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let p = self.pdf_lobes(wi, wo, at);
        if p.is_finite() && p > 0.0 {
            p
        } else {
            0.0
        }
    }

    fn pdf_lobes(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        if wi.z == 0.0 || !(wi.z * wo.z != 0.0) {
            return 0.0;
        }
        let w = self.weights(at);
        let Some([psr, pst, pdr, pdt]) = self.probabilities(&w) else {
            return 0.0;
        };
        let (wi, wo) = (mulsign(wi, wi.z), mulsign(wo, wi.z));
        let reflect = wo.z > 0.0;
        let mut pdf = 0.0;
        if self.p.spec_trans.is_some() {
            let wo_r = upper(wo);
            let wh = (wi + wo_r).unit();
            let jacobian = (1.0 / (4.0 * wo_r.dot(wh))).abs();
            if reflect && micro_compatible(wh, wi, wo, wi.z, true) {
                pdf += psr * w.reflection().pdf(wi, wh) * jacobian;
            }
            if !reflect && micro_compatible(wh, wi, wo, wi.z, false) {
                pdf += pst * w.transmission().pdf(wi, wh) * jacobian;
            }
        }
        if reflect {
            pdf += pdr * cosine_hemisphere_pdf(wo);
        } else if self.p.diff_trans.is_some() {
            pdf += pdt * cosine_hemisphere_pdf(-wo);
        }
        pdf
    }

    /// Chooses a lobe with `u1` and draws its direction with `u2` (seen from `wi`'s side);
    /// the weight is `eval / pdf` of the whole mixture.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        let ci = wi.z;
        if ci == 0.0 || !ci.is_finite() {
            return None;
        }
        let w = self.weights(at);
        let [psr, pst, pdr, _] = self.probabilities(&w)?;
        let wi_t = mulsign(wi, ci);
        let has_st = self.p.spec_trans.is_some();
        let wo = if has_st && u1 < psr {
            let (m, _) = w.reflection().sample(wi_t, u2)?;
            let wo = reflect(wi_t, m);
            (wo.z > 0.0 && micro_compatible(m, wi_t, wo, wi_t.z, true)).then_some(wo)?
        } else if has_st && u1 < psr + pst {
            let (m, _) = w.transmission().sample(wi_t, u2)?;
            let r = reflect(wi_t, m);
            let wo = Vec3::new(r.x, r.y, -r.z);
            (wo.z < 0.0 && micro_compatible(m, wi_t, wo, wi_t.z, false)).then_some(wo)?
        } else if u1 < psr + pst + pdr {
            square_to_cosine_hemisphere(u2)
        } else if self.p.diff_trans.is_some() {
            -square_to_cosine_hemisphere(u2)
        } else {
            return None;
        };
        let wo = mulsign(wo, ci);
        let pdf = self.pdf(wi, wo, at);
        if !(pdf > 0.0) {
            return None;
        }
        let weight = self.eval(wi, wo, at) / pdf;
        weight.is_finite().then_some(BsdfSample {
            wo,
            weight,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }

    /// Calls `f` with every texture the model reads: base colour, roughness, index, then the
    /// lobes' that are on (in the order of [`PrincipledThinParams`]).
    pub fn for_each_texture(&self, f: &mut dyn FnMut(&Texture)) {
        let p = &self.p;
        f(&p.base_color);
        f(&p.roughness);
        f(&p.eta);
        [
            &p.anisotropic,
            &p.spec_trans,
            &p.spec_tint,
            &p.sheen,
            &p.sheen_tint,
            &p.flatness,
            &p.diff_trans,
        ]
        .into_iter()
        .flatten()
        .for_each(&mut *f);
    }

    /// Every lobe is smooth.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// No delta component.
    pub fn has_delta(&self) -> bool {
        false
    }
}

/// The thin sheet's reflection Fresnel: the dielectric `f_dielectric` blended by `spec_tint`
/// toward Schlick's approximation with `r0` the base colour's hue times `((eta-1)/(eta+1))^2`.
fn thin_fresnel(
    f_dielectric: f32,
    spec_tint: Option<f32>,
    base: Color,
    cos_i: f32,
    eta: f32,
) -> Color {
    let tint = spec_tint.unwrap_or(0.0);
    let schlick = match spec_tint {
        Some(_) => {
            let f0 = hue(base) * schlick_r0(eta);
            f0.map(|r0| schlick_fresnel(r0, cos_i, eta))
        }
        None => Color::ZERO,
    };
    schlick.map(|s| lerp(f_dielectric, s, tint))
}

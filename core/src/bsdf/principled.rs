//! Mitsuba 3's `principled` BSDF: Burley's Disney model ("Physically Based Shading at
//! Disney", 2012, and its 2015 extension to transmission) as Mitsuba 3.9.1 writes it, which is
//! what Mitsuba's Blender exporter emits for a Principled BSDF node.
//!
//! Lobes, each weighted as Mitsuba weights it (`m` metallic, `t` spec_trans):
//! - main specular reflection, anisotropic GGX with roughness `roughness^2` (stretched by
//!   `anisotropic`), Fresnel blended between the dielectric's, a Schlick term toward the base
//!   colour (`m`) and one toward its hue (`spec_tint`); from the back only `(1 - m) t` times the
//!   dielectric Fresnel;
//! - main specular transmission through the same microfacets, `(1 - m) t sqrt(base_color)`,
//!   with the radiance scaling `1 / eta^2` (as `roughdielectric`);
//! - clearcoat: GTR1 normals (roughness 0.1 to 0.001 by `clearcoat_gloss`), Schlick Fresnel
//!   with `r0` 0.04, GGX masking of roughness 0.25, weight `clearcoat / 4` (front side);
//! - Burley's diffuse with retro-reflection (blended toward Hanrahan-Krueger's flattened
//!   subsurface by `flatness`), weight `(1 - m)(1 - t)`, and sheen `(1 - m) sheen`, tinted
//!   toward the base colour's hue by `sheen_tint` (front side).
//!
//! A lobe whose parameter the file does not give (or gives as the float 0) is off, as in
//! Mitsuba: the `Option` fields. The index is `eta` or comes from `specular`
//! (`2 / (1 - sqrt(0.08 specular)) - 1`). Sampling and the density are in
//! `principled_sample.rs` (above this file), the lobes' formulas in [`super::principled_lobes`]. Its scene
//! parameters are declared with its loader, in `scene/src/materials/principled.rs`.
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetKind};
use super::principled_lobes::{
    burley_diffuse, clearcoat_alpha, main_alphas, micro_compatible, mulsign, schlick_fresnel,
    sheen_color, smith_ggx1, FresnelBlend, Gtr1,
};
use crate::geometry::ShadingPoint;
use crate::math::{Norm, INV_PI};
use crate::texture::Texture;
use crate::Color;
use alloc::boxed::Box;
use glam::Vec3;

/// How often each lobe is sampled, relative to its weight (Mitsuba's `*_sampling_rate`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplingRates {
    /// `diffuse_reflectance_sampling_rate`.
    pub diffuse: f32,
    /// `main_specular_sampling_rate`.
    pub specular: f32,
    /// `clearcoat_sampling_rate`.
    pub clearcoat: f32,
}

/// Where the relative index comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PrincipledIndex {
    /// `eta` itself (> 0).
    Eta(f32),
    /// Blender's `specular` level (in `[0, 12.5)`).
    Specular(f32),
}

/// The parameters of a [`Principled`], as the scene gives them. A lobe's `Option` is `None`
/// when the lobe is off.
#[derive(Clone, Debug)]
pub struct PrincipledParams {
    /// Base colour.
    pub base_color: Texture,
    /// Roughness of the main lobes (scalar).
    pub roughness: Texture,
    /// Anisotropy (scalar).
    pub anisotropic: Option<Texture>,
    /// Metallic weight (scalar).
    pub metallic: Option<Texture>,
    /// Transmission weight (scalar).
    pub spec_trans: Option<Texture>,
    /// Tint of the dielectric reflection toward the base colour's hue (scalar).
    pub spec_tint: Option<Texture>,
    /// Sheen weight (scalar).
    pub sheen: Option<Texture>,
    /// Tint of the sheen toward the base colour's hue (scalar).
    pub sheen_tint: Option<Texture>,
    /// Blend of the diffuse toward the flattened subsurface approximation (scalar).
    pub flatness: Option<Texture>,
    /// Clearcoat weight (scalar).
    pub clearcoat: Option<Texture>,
    /// Clearcoat gloss (scalar).
    pub clearcoat_gloss: Texture,
    /// The index.
    pub index: PrincipledIndex,
    /// Lobe sampling rates.
    pub rates: SamplingRates,
}

/// Mitsuba 3's principled BSDF.
#[derive(Clone, Debug)]
pub struct Principled {
    /// Boxed: eleven textures would make every `Bsdf` as large.
    pub(super) p: Box<PrincipledParams>,
    /// Relative index of refraction, inside over outside.
    pub(super) eta: f32,
}

/// The scalar weights at one surface point.
#[derive(Clone, Copy, Debug)]
pub(super) struct Weights {
    pub roughness: f32,
    pub anisotropic: Option<f32>,
    pub metallic: Option<f32>,
    pub spec_trans: f32,
    pub clearcoat: f32,
}

impl Weights {
    /// Weight of the diffuse lobes, `(1 - metallic)(1 - spec_trans)`.
    pub(crate) fn brdf(&self) -> f32 {
        (1.0 - self.metallic.unwrap_or(0.0)) * (1.0 - self.spec_trans)
    }
    /// Weight of the transmissive lobe, `(1 - metallic) spec_trans`.
    pub fn bsdf(&self) -> f32 {
        (1.0 - self.metallic.unwrap_or(0.0)) * self.spec_trans
    }
    /// The main lobes' GGX distribution, visible normals sampled.
    pub fn distribution(&self) -> Microfacet {
        let (alpha_u, alpha_v) = main_alphas(self.roughness, self.anisotropic);
        Microfacet {
            kind: MicrofacetKind::Ggx,
            alpha_u,
            alpha_v,
            sample_visible: true,
        }
    }
}

/// The half vector of `wi` and `wo` (the generalised one for a refraction, `eta_path` the
/// index on `wo`'s side over `wi`'s), turned to the outside.
#[inline]
pub(super) fn half_vector(wi: Vec3, wo: Vec3, reflect: bool, eta_path: f32) -> Vec3 {
    let h = (wi + wo * if reflect { 1.0 } else { eta_path }).unit();
    mulsign(h, h.z)
}

impl Principled {
    /// The model for `p`. With a transmission lobe, an index of exactly 1 (`eta` 1 or
    /// `specular` 0) is moved to 1.001 (`specular` 1e-3), as Mitsuba does.
    pub fn new(p: PrincipledParams) -> Self {
        let st = p.spec_trans.is_some();
        let eta = match p.index {
            PrincipledIndex::Eta(e) => {
                if st && e == 1.0 {
                    1.001
                } else {
                    e
                }
            }
            PrincipledIndex::Specular(s) => {
                let s = if st && s == 0.0 { 1e-3 } else { s };
                2.0 * (1.0 / (1.0 - crate::math::sqrt(0.08 * s))) - 1.0
            }
        };
        Principled {
            p: Box::new(p),
            eta,
        }
    }

    /// The relative index used (inside over outside).
    pub fn eta(&self) -> f32 {
        self.eta
    }

    /// Whether the transmission lobe is on.
    pub(super) fn has_spec_trans(&self) -> bool {
        self.p.spec_trans.is_some()
    }

    /// Whether the clearcoat lobe is on.
    pub(super) fn has_clearcoat(&self) -> bool {
        self.p.clearcoat.is_some()
    }

    /// The weights at `at`.
    pub(super) fn weights(&self, at: ShadingPoint) -> Weights {
        let opt = |t: &Option<Texture>| t.as_ref().map(|t| t.eval_1(at));
        Weights {
            roughness: self.p.roughness.eval_1(at),
            anisotropic: opt(&self.p.anisotropic),
            metallic: opt(&self.p.metallic),
            spec_trans: opt(&self.p.spec_trans).unwrap_or(0.0),
            clearcoat: opt(&self.p.clearcoat).unwrap_or(0.0),
        }
    }

    /// The clearcoat's normal distribution at `at`.
    pub(super) fn clearcoat_distribution(&self, at: ShadingPoint) -> Gtr1 {
        Gtr1 {
            alpha: clearcoat_alpha(self.p.clearcoat_gloss.eval_1(at)),
        }
    }

    /// `f(wi, wo) |cos theta_o|`: reflection when `wi` and `wo` are on one side, transmission
    /// when on opposite sides; 0 at grazing `wi`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let r = self.eval_lobes(wi, wo, at);
        if r.is_finite() {
            r
        } else {
            Color::ZERO
        }
    }

    fn eval_lobes(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let (ci, co) = (wi.z, wo.z);
        if ci == 0.0 || !(ci * co != 0.0) {
            return Color::ZERO;
        }
        let w = self.weights(at);
        let base = self.p.base_color.eval(at);
        let (brdf, bsdf) = (w.brdf(), w.bsdf());
        let reflect = ci * co > 0.0;
        let front = ci > 0.0;
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let distr = w.distribution();
        let wh = half_vector(wi, wo, reflect, eta_path);
        let (cos_ih, cos_oh) = (wi.dot(wh), wo.dot(wh));
        let f = fresnel_dielectric(cos_ih, self.eta).f;
        let d = distr.d(wh);
        let g = distr.g(wi, wo, wh);
        let mut value = Color::ZERO;

        if reflect && micro_compatible(wh, wi, wo, ci, true) {
            if f > 0.0 {
                let blend = FresnelBlend {
                    metallic: w.metallic,
                    spec_tint: self.p.spec_tint.as_ref().map(|t| t.eval_1(at)),
                    base_color: base,
                    bsdf,
                    eta: self.eta,
                };
                value += blend.eval(f, cos_ih, front) * (d * g / (4.0 * ci.abs()));
            }
            if front && self.has_clearcoat() && w.clearcoat > 0.0 {
                let fcc = schlick_fresnel(0.04, cos_ih, self.eta);
                let dcc = self.clearcoat_distribution(at).d(wh);
                let gcc = smith_ggx1(wi, wh, 0.25) * smith_ggx1(wo, wh, 0.25);
                value += Color::splat(w.clearcoat * 0.25 * fcc * dcc * gcc * co.abs());
            }
        }
        if !reflect
            && self.has_spec_trans()
            && bsdf > 0.0
            && f < 1.0
            && micro_compatible(wh, wi, wo, ci, false)
        {
            let den = cos_ih + eta_path * cos_oh;
            // The radiance scaling 1 / eta_path^2 cancels the Jacobian's eta_path^2.
            let t = ((1.0 - f) * d * g * cos_ih * cos_oh / (ci * den * den)).abs();
            value += base.map(crate::math::sqrt) * (bsdf * t);
        }
        if reflect && front && brdf > 0.0 {
            value += self.diffuse_and_sheen(&w, base, brdf, ci, co, wh.dot(wo), at);
        }
        value
    }

    /// The diffuse, retro-reflection, flattened-subsurface and sheen terms (front side,
    /// reflection), `|cos theta_o|` included; `cos_d` is `wo.h`.
    #[allow(clippy::too_many_arguments)]
    fn diffuse_and_sheen(
        &self,
        w: &Weights,
        base: Color,
        brdf: f32,
        ci: f32,
        co: f32,
        cos_d: f32,
        at: ShadingPoint,
    ) -> Color {
        let (ci, co) = (ci.abs(), co.abs());
        let flatness = self.p.flatness.as_ref().map(|t| t.eval_1(at));
        let shape = burley_diffuse(w.roughness, flatness, ci, co, cos_d);
        let mut value = base * (brdf * co * INV_PI * shape);
        let metallic = w.metallic.unwrap_or(0.0);
        if let Some(sheen) = &self.p.sheen {
            let sheen = sheen.eval_1(at);
            if sheen > 0.0 && 1.0 - metallic > 0.0 {
                let tint = self.p.sheen_tint.as_ref().map(|t| t.eval_1(at));
                value += sheen_color(tint, base, cos_d) * (sheen * (1.0 - metallic) * co);
            }
        }
        value
    }

    /// Calls `f` with every texture the model reads: base colour, roughness, the lobes' that
    /// are on (in the order of [`PrincipledParams`]), clearcoat gloss.
    pub fn for_each_texture(&self, f: &mut dyn FnMut(&Texture)) {
        let p = &self.p;
        f(&p.base_color);
        f(&p.roughness);
        [
            &p.anisotropic,
            &p.metallic,
            &p.spec_trans,
            &p.spec_tint,
            &p.sheen,
            &p.sheen_tint,
            &p.flatness,
            &p.clearcoat,
        ]
        .into_iter()
        .flatten()
        .for_each(&mut *f);
        if p.clearcoat.is_some() {
            f(&p.clearcoat_gloss);
        }
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

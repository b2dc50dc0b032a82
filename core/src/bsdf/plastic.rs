//! Smooth plastic (Mitsuba 3's `plastic`): a smooth dielectric coating over a diffuse base,
//! one-sided (the back side is black).
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/plastic.rs`.
//!
//! Model (as Mitsuba 3): the coating reflects `F(cos theta_i)` as a delta lobe; the rest
//! refracts in, scatters diffusely at the base, and leaves through the coating with
//! `1 - F(cos theta_o)`, scaled by `1 / eta^2`. Light reflected back down by the coating's inner
//! side is accounted for by dividing the base albedo `d` by `1 - Fdr_int` (or by
//! `1 - d Fdr_int` per channel with `nonlinear`), `Fdr_int` being the diffuse Fresnel
//! reflectance of the inside. The coating is chosen with probability proportional to
//! `F(cos theta_i) w` against `(1 - F(cos theta_i)) (1 - w)`, with `w` = mean specular over
//! (mean diffuse + mean specular) reflectance; `pdf` includes the base's share.
use super::fresnel::fresnel_dielectric;
use super::plastic_common::{
    coating_probability, fresnel_diffuse_reflectance, internal_scattering, specular_sampling_weight,
};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::INV_PI;
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Smooth coating over a diffuse base.
#[derive(Clone, Debug)]
pub struct Plastic {
    pub(super) diffuse: Texture,
    pub(super) specular: Texture,
    eta: f32,
    nonlinear: bool,
    inv_eta_2: f32,
    fdr_int: f32,
    spec_weight: f32,
}

impl Plastic {
    /// A smooth plastic with base albedo `diffuse`, coating factor `specular`, relative index
    /// `eta = int_ior / ext_ior` (> 0) and the `nonlinear` switch.
    pub fn new(diffuse: Texture, specular: Texture, eta: f32, nonlinear: bool) -> Self {
        let spec_weight = specular_sampling_weight(&diffuse, &specular);
        Plastic {
            diffuse,
            specular,
            eta,
            nonlinear,
            inv_eta_2: 1.0 / (eta * eta),
            fdr_int: fresnel_diffuse_reflectance(1.0 / eta),
            spec_weight,
        }
    }

    /// The base's reflected radiance factor `f cos theta_o` for front-side `wi`, `wo`, given
    /// the coating's reflectance `fi` toward `wi`.
    fn diffuse_part(&self, fi: f32, wo: Vec3, at: ShadingPoint) -> Color {
        let fo = fresnel_dielectric(wo.z, self.eta).f;
        let d = internal_scattering(self.diffuse.eval(at), self.fdr_int, self.nonlinear);
        d * (INV_PI * wo.z * self.inv_eta_2 * (1.0 - fi) * (1.0 - fo))
    }

    /// `f(wi, wo) cos theta_o` of the diffuse base (the coating is a delta lobe).
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return Color::ZERO;
        }
        let fi = fresnel_dielectric(wi.z, self.eta).f;
        self.diffuse_part(fi, wo, at)
    }

    /// Cosine density times the probability of choosing the base.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, _at: ShadingPoint) -> f32 {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return 0.0;
        }
        let fi = fresnel_dielectric(wi.z, self.eta).f;
        match coating_probability(fi, self.spec_weight) {
            Some(ps) => (1.0 - ps) * cosine_hemisphere_pdf(wo),
            None => 0.0,
        }
    }

    /// `u1` chooses the coating's mirror reflection or the base; the base is sampled by the
    /// cosine.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let fi = fresnel_dielectric(wi.z, self.eta).f;
        let ps = coating_probability(fi, self.spec_weight)?;
        if u1 < ps {
            let weight = self.specular.eval(at) * (fi / ps);
            return Some(BsdfSample::delta(Vec3::new(-wi.x, -wi.y, wi.z), weight, ps));
        }
        let wo = square_to_cosine_hemisphere(u2);
        let pdf = (1.0 - ps) * cosine_hemisphere_pdf(wo);
        if !(pdf > 0.0 && wo.z > 0.0) {
            return None;
        }
        Some(BsdfSample {
            wo,
            weight: self.diffuse_part(fi, wo, at) / pdf,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }

    /// The base is smooth.
    pub fn has_smooth(&self) -> bool {
        true
    }
    /// The coating is a delta reflection.
    pub fn has_delta(&self) -> bool {
        true
    }
}

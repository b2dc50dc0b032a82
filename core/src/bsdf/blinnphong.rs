//! Chalmers' Blinn-Phong dielectric layer over an optional nested model (`blinnphong`), from
//! the Chalmers path-tracer tutorial (tasks 3 and 6).
//!
//! Its scene parameters are declared with its loader, in
//! `scene/src/materials/chalmers.rs`.
//!
//! With `h = normalize(wi + wo)` and both directions above the surface:
//! - `F = r0 + (1 - r0)(1 - h.wi)^5`, `D = (s + 2)/(2 pi) (n.h)^s`,
//!   `G = min(1, 2 (n.h)(n.wo)/(wo.h), 2 (n.h)(n.wi)/(wo.h))`;
//! - `f = F D G / (4 (n.wi)(n.wo)) + T f_base(wi, wo)` with the base's share
//!   `T = (1 - F(n.wi)) (1 - F(n.wo))`, `F(c) = r0 + (1 - r0)(1 - c)^5` at the macro normal:
//!   light reaches the base through the coating and leaves through it again. (The tutorial
//!   weights the base by `1 - F(h.wi)`, the Fresnel factor of the pair's half vector; with a
//!   white diffuse base that returns up to 1.8 times the incident energy at grazing incidence,
//!   e.g. 1.16 at 80 degrees for `s` = 25, `r0` = 0.04; Tessera's `T` keeps the albedo <= 1,
//!   see `scripts/blinnphong_albedo.py --energy`.) A base direction below the surface (a
//!   transmitting base) crosses the coating once: `T = 1 - F(n.wi)`.
//! - One-sided: `wi` below the surface scatters nothing.
//!
//! Sampling, as the tutorial's `sample_wi`: with a base, the coating lobe and the base are each
//! chosen with probability 1/2 (the coating alone: always the lobe). The lobe draws `h` with
//! density `(s + 1)/(2 pi) (n.h)^s` (`cos theta_h = u^(1/(s+1))`) and reflects `wi` about it,
//! density `p(h) / (4 wo.h)`; draws whose reflection leaves the hemisphere are rejected. The
//! reported `pdf` is the exact mixture of both strategies and `weight = eval / pdf`; a delta
//! component of the base keeps its discrete probability times 1/2.
use super::fresnel::schlick;
use super::model::Model;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::math::{safe_sqrt, sincos_turns, Norm, INV_TWO_PI};
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// The tutorial's Blinn-Phong microfacet lobe: exponent and Schlick `r0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Lobe {
    /// Blinn-Phong exponent `s >= 0`.
    pub shininess: f32,
    /// Fresnel reflectance at normal incidence, in `[0, 1]`.
    pub r0: f32,
}

impl Lobe {
    /// The share `T` of the base: `(1 - F(n.wi))(1 - F(n.wo))`, or `1 - F(n.wi)` for `wo`
    /// below the surface.
    pub(crate) fn base_share(&self, wi: Vec3, wo: Vec3) -> f32 {
        let t_in = 1.0 - schlick(self.r0, wi.z);
        if wo.z > 0.0 {
            t_in * (1.0 - schlick(self.r0, wo.z))
        } else {
            t_in
        }
    }

    /// `F D G / (4 (n.wi))`: the reflection BRDF times `cos theta_o` (0 off the hemisphere).
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        let h = (wi + wo).unit_or_zero();
        let (nh, oh) = (h.z, wo.dot(h));
        if !(nh > 0.0 && oh > 0.0) {
            return 0.0;
        }
        let s = self.shininess;
        let d = (s + 2.0) * INV_TWO_PI * libm::powf(nh, s);
        let g = (2.0 * nh * wo.z / oh).min(2.0 * nh * wi.z / oh).min(1.0);
        let f = schlick(self.r0, h.dot(wi));
        let v = f * d * g / (4.0 * wi.z);
        if v.is_finite() {
            v
        } else {
            0.0
        }
    }

    /// Density of [`Lobe::sample`] producing `wo`.
    pub fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        let h = (wi + wo).unit_or_zero();
        let (nh, oh) = (h.z, wo.dot(h));
        if !(nh > 0.0 && oh > 0.0) {
            return 0.0;
        }
        let s = self.shininess;
        let p = (s + 1.0) * INV_TWO_PI * libm::powf(nh, s) / (4.0 * oh);
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }

    /// Reflects `wi` about a half vector drawn with density `(s+1)/(2 pi) (n.h)^s`; `None` when
    /// the reflection leaves the upper hemisphere.
    pub fn sample(&self, wi: Vec3, u: Vec2) -> Option<Vec3> {
        if wi.z <= 0.0 {
            return None;
        }
        let cos_t = libm::powf(u.x, 1.0 / (self.shininess + 1.0));
        let sin_t = safe_sqrt(1.0 - cos_t * cos_t);
        let (sin_p, cos_p) = sincos_turns(u.y);
        let h = Vec3::new(sin_t * cos_p, sin_t * sin_p, cos_t);
        let ih = wi.dot(h);
        if !(ih > 0.0) {
            return None;
        }
        let wo = (2.0 * ih * h - wi).unit_or_zero();
        (wo.z > 0.0).then_some(wo)
    }
}

/// Chalmers' Blinn-Phong dielectric layer over a nested model (`blinnphong`).
#[derive(Clone, Debug)]
pub struct BlinnPhong<B> {
    lobe: Lobe,
    pub(super) base: Option<Box<B>>,
}

impl<B: Model> BlinnPhong<B> {
    /// A coating of exponent `shininess >= 0` and Schlick `r0` in `[0, 1]` over `base` (which
    /// receives the light the coating transmits), if any.
    pub fn new(shininess: f32, r0: f32, base: Option<Box<B>>) -> Self {
        BlinnPhong {
            lobe: Lobe { shininess, r0 },
            base,
        }
    }

    /// Probability of sampling the coating lobe.
    fn p_lobe(&self) -> f32 {
        if self.base.is_some() {
            0.5
        } else {
            1.0
        }
    }

    /// `f(wi, wo) |cos theta_o|`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        if !(wi.z > 0.0) {
            return Color::ZERO;
        }
        let mut v = Color::splat(self.lobe.eval(wi, wo));
        if let Some(base) = &self.base {
            v += base.eval(wi, wo, at) * self.lobe.base_share(wi, wo);
        }
        v
    }

    /// Density of the smooth components: the mixture of the lobe's and the base's.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        if !(wi.z > 0.0) {
            return 0.0;
        }
        let p = self.p_lobe();
        let mut d = p * self.lobe.pdf(wi, wo);
        if let Some(base) = &self.base {
            d += (1.0 - p) * base.pdf(wi, wo, at);
        }
        d
    }

    /// Samples the lobe or the base (probability 1/2 each), weight against the mixture.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if !(wi.z > 0.0) {
            return None;
        }
        let p = self.p_lobe();
        let (wo, eta) = match &self.base {
            Some(base) if u1 >= p => {
                let s = base.sample(wi, ((u1 - p) / (1.0 - p)).min(1.0 - f32::EPSILON), u2, at)?;
                if s.delta {
                    let t = self.lobe.base_share(wi, s.wo);
                    return Some(BsdfSample {
                        weight: s.weight * (t / (1.0 - p)),
                        pdf: s.pdf * (1.0 - p),
                        ..s
                    });
                }
                (s.wo, s.eta)
            }
            _ => (self.lobe.sample(wi, u2)?, 1.0),
        };
        let pdf = self.pdf(wi, wo, at);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let weight = self.eval(wi, wo, at) / pdf;
        weight.is_finite().then_some(BsdfSample {
            wo,
            weight,
            pdf,
            delta: false,
            eta,
        })
    }

    /// Always smooth (the lobe).
    pub fn has_smooth(&self) -> bool {
        true
    }

    /// Whether the base has a delta component.
    pub fn has_delta(&self) -> bool {
        self.base.as_ref().is_some_and(|b| b.has_delta())
    }
}

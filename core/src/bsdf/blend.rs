//! Linear blend of two models (`blendbsdf` as in Mitsuba 3; Chalmers' `LinearBlend` is the
//! alias `blend`).
//!
//! A texture weight is read as a scalar (`Texture::eval_1`). `f = (1 - w) f0 + w f1`: the
//! weight belongs to the second model, so Chalmers' `LinearBlend(w, a, b) = w a + (1 - w) b` is
//! `blend` with `b` first and `a` second. Its scene parameters are declared with its loader, in
//! `scene/src/materials/basic.rs`.
//!
//! Sampling chooses the second model when `u1 < w` (then reuses `u1 / w`), the first otherwise
//! (`(u1 - w) / (1 - w)`), as Mitsuba 3 does. A smooth sample reports the mixed density
//! `(1 - w) p0 + w p1` and `weight = eval / pdf`; a delta sample keeps its own weight and its
//! discrete probability times the probability of choosing its model.
use super::model::Model;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// Linear blend of two models (`blendbsdf`, Chalmers' `blend`).
#[derive(Clone, Debug)]
pub struct Blend<B> {
    /// Share of `second`, in `[0, 1]`.
    pub weight: Texture,
    /// The model weighted by `1 - weight`.
    pub first: Box<B>,
    /// The model weighted by `weight`.
    pub second: Box<B>,
}

impl<B: Model> Blend<B> {
    fn w(&self, at: ShadingPoint) -> f32 {
        let w = self.weight.eval_1(at);
        if w.is_finite() {
            w.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
    /// `f(wi, wo) |cos theta_o|`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let w = self.w(at);
        let mut v = Color::ZERO;
        if w < 1.0 {
            v += self.first.eval(wi, wo, at) * (1.0 - w);
        }
        if w > 0.0 {
            v += self.second.eval(wi, wo, at) * w;
        }
        v
    }
    /// Density of the smooth components.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let w = self.w(at);
        let mut p = 0.0;
        if w < 1.0 {
            p += self.first.pdf(wi, wo, at) * (1.0 - w);
        }
        if w > 0.0 {
            p += self.second.pdf(wi, wo, at) * w;
        }
        p
    }
    /// Samples one of the two models by weight.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        let w = self.w(at);
        let (chosen, prob, u) = if u1 < w {
            (&self.second, w, u1 / w)
        } else {
            (&self.first, 1.0 - w, (u1 - w) / (1.0 - w))
        };
        let s = chosen.sample(wi, u.clamp(0.0, 1.0 - f32::EPSILON), u2, at)?;
        if s.delta {
            return Some(BsdfSample {
                pdf: s.pdf * prob,
                ..s
            });
        }
        let pdf = self.pdf(wi, s.wo, at);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let weight = self.eval(wi, s.wo, at) / pdf;
        weight
            .is_finite()
            .then_some(BsdfSample { weight, pdf, ..s })
    }
    /// Whether either model has a smooth component.
    pub fn has_smooth(&self) -> bool {
        self.first.has_smooth() || self.second.has_smooth()
    }
    /// Whether either model has a delta component.
    pub fn has_delta(&self) -> bool {
        self.first.has_delta() || self.second.has_delta()
    }
}

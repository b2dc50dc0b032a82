//! Opacity mask over a model (`mask`), as in Mitsuba 3: a surface that is partly not there.
//!
//! A texture opacity is read as a scalar (`Texture::eval_1`). Its scene parameters are declared
//! with its loader, in `scene/src/materials/basic.rs`.
//!
//! With opacity `a`: `eval` and `pdf` are `a` times the nested model's (Mitsuba 3 measured); a
//! ray passes straight through (`wo = -wi`, weight 1, `eta` 1) with probability `1 - a`, a
//! delta component. Sampling chooses the nested model when `u1 < a` (reusing `u1 / a`); its
//! smooth samples keep their weight and report the density `a p`, its delta samples their
//! probability times `a`.
use super::model::Model;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// Opacity mask over a model (`mask`).
#[derive(Clone, Debug)]
pub struct Mask<B> {
    /// Probability that the surface is there, in `[0, 1]`.
    pub opacity: Texture,
    /// The model where it is.
    pub nested: Box<B>,
}

impl<B: Model> Mask<B> {
    fn a(&self, at: ShadingPoint) -> f32 {
        let a = self.opacity.eval_1(at);
        if a.is_finite() {
            a.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
    /// `opacity f(wi, wo) |cos theta_o|`.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let a = self.a(at);
        if a > 0.0 {
            self.nested.eval(wi, wo, at) * a
        } else {
            Color::ZERO
        }
    }
    /// `opacity` times the nested density.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let a = self.a(at);
        if a > 0.0 {
            self.nested.pdf(wi, wo, at) * a
        } else {
            0.0
        }
    }
    /// Passes through with probability `1 - opacity`, else samples the nested model.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        let a = self.a(at);
        if u1 >= a {
            return Some(BsdfSample::delta(-wi, Color::ONE, 1.0 - a));
        }
        let s = self
            .nested
            .sample(wi, (u1 / a).min(1.0 - f32::EPSILON), u2, at)?;
        Some(BsdfSample {
            pdf: s.pdf * a,
            ..s
        })
    }
    /// Whether the nested model has a smooth component.
    pub fn has_smooth(&self) -> bool {
        self.nested.has_smooth()
    }
    /// Always: the pass-through is a delta component.
    pub fn has_delta(&self) -> bool {
        true
    }
}

//! Two-sided adapter: a model for the front and one for the back of a surface.
//!
//! A ray arriving from the back sees the back model as if the surface were flipped. Its scene
//! parameters are declared with its loader, in `scene/src/materials/basic.rs`.
use super::model::Model;
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// Front and back BSDFs.
#[derive(Clone, Debug)]
pub struct TwoSided<B> {
    /// Model seen from the side the normal points to.
    pub front: Box<B>,
    /// Model seen from the other side.
    pub back: Box<B>,
}

/// Calls a side's method directly when it is `diffuse` (the common two-sided material, which
/// then inlines), through the side's own dispatch otherwise; the same values either way.
macro_rules! leaf {
    ($side:expr, $b:ident => $call:expr) => {
        match $side.as_diffuse() {
            Some($b) => $call,
            None => {
                let $b = $side;
                $call
            }
        }
    };
}

#[inline]
fn flip(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}

impl<B: Model> TwoSided<B> {
    /// Evaluates the side `wi` is on.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        if wi.z >= 0.0 {
            leaf!(&*self.front, b => b.eval(wi, wo, at))
        } else {
            leaf!(&*self.back, b => b.eval(flip(wi), flip(wo), at))
        }
    }
    /// Density of the side `wi` is on.
    #[inline]
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        if wi.z >= 0.0 {
            leaf!(&*self.front, b => b.pdf(wi, wo, at))
        } else {
            leaf!(&*self.back, b => b.pdf(flip(wi), flip(wo), at))
        }
    }
    /// Samples the side `wi` is on.
    #[inline]
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        if wi.z >= 0.0 {
            leaf!(&*self.front, b => b.sample(wi, u1, u2, at))
        } else {
            let mut s = leaf!(&*self.back, b => b.sample(flip(wi), u1, u2, at))?;
            s.wo = flip(s.wo);
            Some(s)
        }
    }
    /// Whether either side has a smooth component.
    #[inline]
    pub fn has_smooth(&self) -> bool {
        leaf!(&*self.front, b => b.has_smooth()) || leaf!(&*self.back, b => b.has_smooth())
    }
    /// Whether either side has a delta component.
    #[inline]
    pub fn has_delta(&self) -> bool {
        leaf!(&*self.front, b => b.has_delta()) || leaf!(&*self.back, b => b.has_delta())
    }
}

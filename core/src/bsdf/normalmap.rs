//! Normal mapping (`normalmap`, Mitsuba 3): the shading normal is read from an RGB texture in
//! tangent space and the nested model is evaluated around it.
//!
//! The texture's colour `c` in `[0, 1]^3` is the normal `2c - 1` in the local shading frame,
//! whose first tangent follows `dp/du` and whose second is `n x s` (so green is the `+v`
//! tangent's side when `dp/du` and `dp/dv` are right-handed about the normal). The frame
//! around it, the flip of normals that face away, and the shadowing term are those of
//! [`super::perturbed`]. Its scene parameters are declared with its loader, in
//! `scene/src/materials/maps.rs`.
use super::model::Model;
use super::perturbed::{PerturbOptions, Tilted};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// A model seen through a tangent-space normal map (`normalmap`).
#[derive(Clone, Debug)]
pub struct NormalMap<B> {
    /// RGB texture of normals mapped to `[0, 1]` (`(n + 1) / 2`), read without sRGB decoding.
    pub normalmap: Texture,
    /// The model evaluated in the perturbed frame.
    pub nested: Box<B>,
    /// How the perturbed frame is built and weighted.
    pub options: PerturbOptions,
}

impl<B: Model> NormalMap<B> {
    #[inline]
    fn tilted(&self, wi: Vec3, at: ShadingPoint) -> Tilted {
        let n = self.normalmap.eval(at) * 2.0 - Color::ONE;
        Tilted::new(n, wi, self.options)
    }
    /// The nested value in the perturbed frame.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        self.tilted(wi, at).eval(&*self.nested, wi, wo, at)
    }
    /// The nested density in the perturbed frame.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        self.tilted(wi, at).pdf(&*self.nested, wi, wo, at)
    }
    /// Samples the nested model in the perturbed frame.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        self.tilted(wi, at).sample(&*self.nested, wi, u1, u2, at)
    }
    /// Whether the nested model has a smooth component.
    pub fn has_smooth(&self) -> bool {
        self.nested.has_smooth()
    }
    /// Whether the nested model has a delta component.
    pub fn has_delta(&self) -> bool {
        self.nested.has_delta()
    }
}

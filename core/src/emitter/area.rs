//! Area light: radiance leaving the front side of a shape (one-sided, as in Mitsuba 3), the same
//! everywhere or read from a texture at the surface's uv.
//!
//! Scene parameters (`<emitter type="area">`, nested in a `<shape>`): `radiance` (rgb or
//! texture, required; declared in `scene/src/emitters/area.rs`). A textured light is still
//! sampled by area (or by solid angle for spheres) and its radiance looked up at the sampled
//! point's uv, which is unbiased; Mitsuba 3 instead samples the texture's uv distribution,
//! which only changes the noise.
//! Sampling: spheres seen from outside by solid angle (the cone toward them), every other shape
//! uniformly by area (meshes choose a triangle by area). Points behind a flat light get no
//! sample at all ([`Behind`], set when the scene is built).
use super::sample::{EmitterCtx, EmitterSample};
use crate::geometry::{Interaction, SampleToward};
use crate::light::Behind;
use crate::math::offset_ray_origin;
use crate::texture::Texture;
use crate::Color;
use glam::{Vec2, Vec3};

/// Emission from a shape.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// Index of the shape.
    pub shape: u32,
    /// Emitted radiance; for a textured light, the texture's mean (what light selection and
    /// power estimates use).
    pub radiance: Color,
    /// Radiance varying over the surface by uv, when given as a texture.
    pub texture: Option<Texture>,
    /// Where none of its light arrives, for a flat mesh (set when the `Scene` is built).
    pub behind: Option<Behind>,
}

impl AreaLight {
    /// The light of shape `shape` with radiance `radiance` (its half-space is found when the
    /// scene is built).
    pub fn new(shape: u32, radiance: Color) -> Self {
        AreaLight {
            shape,
            radiance,
            texture: None,
            behind: None,
        }
    }
    /// The light of shape `shape` whose radiance is `texture` over the shape's uv.
    pub fn textured(shape: u32, texture: Texture) -> Self {
        AreaLight {
            shape,
            radiance: texture.mean_value(),
            texture: Some(texture),
            behind: None,
        }
    }
    /// Radiance leaving a point with shading normal `ns` and texture coordinates `uv` toward
    /// the unit direction `w`.
    #[inline]
    pub fn eval(&self, ns: Vec3, w: Vec3, uv: Vec2) -> Color {
        if ns.dot(w) > 0.0 {
            match &self.texture {
                None => self.radiance,
                Some(t) => t.eval(uv),
            }
        } else {
            Color::ZERO
        }
    }
    /// Samples a point on the shape for `it`.
    #[inline]
    pub fn sample(&self, ctx: &EmitterCtx, it: &Interaction, u: Vec2) -> Option<EmitterSample> {
        if self.behind.is_some_and(|b| b.contains(it.p)) {
            return None;
        }
        let shape = &ctx.shapes[self.shape as usize];
        let SampleToward { ps, pdf, d, dist } =
            shape.sample_toward(it.p, u, ctx.disks, self.texture.is_some())?;
        if !(dist > 0.0) {
            return None;
        }
        let wo = d / dist;
        let le = self.eval(ps.ns, -wo, ps.uv);
        if le == Color::ZERO || !(pdf > 0.0) {
            return None;
        }
        let target = offset_ray_origin(ps.p, ps.p_err, ps.ng, -d);
        Some(EmitterSample {
            wo,
            target: Some(target),
            weight: le / pdf,
            pdf,
            delta: false,
        })
    }
    /// Density of `sample` from `r` for the point `p` with geometric normal `ng`.
    pub fn pdf(&self, ctx: &EmitterCtx, r: Vec3, p: Vec3, ng: Vec3) -> f32 {
        ctx.shapes[self.shape as usize].pdf_from(r, p, ng, ctx.disks)
    }
}

//! Area light: uniform radiance leaving the front side of a shape (one-sided, as in Mitsuba 3).
//!
//! Scene parameters (`<emitter type="area">`, nested in a `<shape>`): `radiance` (rgb, required).
//! Sampling: spheres seen from outside by solid angle (the cone toward them), every other shape
//! uniformly by area (meshes choose a triangle by area). Points behind a flat light get no
//! sample at all ([`Behind`], set when the scene is built).
use super::sample::{EmitterCtx, EmitterSample};
use crate::geometry::{Interaction, SampleToward};
use crate::light::Behind;
use crate::math::offset_ray_origin;
use crate::Color;
use glam::{Vec2, Vec3};

/// Emission from a shape.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// Index of the shape.
    pub shape: u32,
    /// Emitted radiance.
    pub radiance: Color,
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
            behind: None,
        }
    }
    /// Radiance leaving a point with shading normal `ns` toward the unit direction `w`.
    #[inline]
    pub fn eval(&self, ns: Vec3, w: Vec3) -> Color {
        if ns.dot(w) > 0.0 {
            self.radiance
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
        let SampleToward { ps, pdf, d, dist } = shape.sample_toward(it.p, u, ctx.disks)?;
        if !(dist > 0.0) {
            return None;
        }
        let wo = d / dist;
        let le = self.eval(ps.ns, -wo);
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

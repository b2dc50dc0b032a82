//! A surface interaction: where a ray met a shape, with everything shading needs.
use crate::math::{offset_ray_origin, Frame, Ray};
use glam::{Vec2, Vec3};

/// The fraction of a shadow segment left out at its far end (its target carries its own offset).
pub const SHADOW_EPSILON: f32 = 1e-4;

/// A point on a surface reached by a ray.
#[derive(Clone, Copy, Debug)]
pub struct Interaction {
    /// Position.
    pub p: Vec3,
    /// Absolute error bound of `p`, per component.
    pub p_err: Vec3,
    /// Ray parameter of the hit.
    pub t: f32,
    /// Unit geometric normal (after `flip_normals`).
    pub ng: Vec3,
    /// Shading frame (interpolated normal as +z).
    pub frame: Frame,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Shape index.
    pub shape: u32,
    /// Unit direction back toward the ray's origin, in world space.
    pub wi: Vec3,
}

impl Interaction {
    /// A ray leaving this point in direction `d`, offset so it cannot re-hit this surface.
    #[inline]
    pub fn spawn_ray(&self, d: Vec3) -> Ray {
        Ray::new(offset_ray_origin(self.p, self.p_err, self.ng, d), d)
    }
    /// A shadow segment from this point to `target` (itself already offset off its surface);
    /// it covers `[0, 1 - SHADOW_EPSILON)` of the segment.
    #[inline]
    pub fn spawn_ray_to(&self, target: Vec3) -> Ray {
        let o = offset_ray_origin(self.p, self.p_err, self.ng, target - self.p);
        Ray {
            o,
            d: target - o,
            t_max: 1.0 - SHADOW_EPSILON,
        }
    }
}

//! Mitsuba 3's `orthographic` sensor: parallel rays along the camera's local +z from the
//! rectangle `[-1, 1] x [-1/aspect, 1/aspect]` of its near plane, so `to_world`'s scale sets
//! the size of the view (a scale of `s` sees a `2s`-wide strip). Rays start on the plane
//! `z = near_clip` and run `far_clip - near_clip`, as in Mitsuba 3.
use crate::math::{Norm, Ray, Transform};
use glam::{Vec2, Vec3};

/// An orthographic projection.
#[derive(Clone, Debug)]
pub struct Orthographic {
    /// Distance to the near clip plane, in camera space.
    pub near: f32,
    /// Distance to the far clip plane, in camera space.
    pub far: f32,
}

impl Orthographic {
    /// The ray, in world space, through film position `pos` of a `width` x `height` film.
    #[inline]
    pub fn generate_ray(
        &self,
        to_world: &Transform,
        pos: Vec2,
        (width, height): (u32, u32),
    ) -> Ray {
        let (w, h) = (width as f32, height as f32);
        let x = 1.0 - 2.0 * pos.x / w;
        let y = (1.0 - 2.0 * pos.y / h) * h / w;
        Ray {
            o: to_world.point(Vec3::new(x, y, self.near)),
            d: to_world.vector(Vec3::Z).unit(),
            t_max: self.far - self.near,
        }
    }
}

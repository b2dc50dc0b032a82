//! A camera ray's differentials as Mitsuba 3's sensors make them (`sample_ray_differential`):
//! the rays through the film point one pixel to the right and one pixel down, which the `aov`
//! integrator's `duv_dx` and `duv_dy` outputs measure the texture coordinates' change along.
//!
//! A pinhole (`perspective`) keeps the origin and turns the direction; an `orthographic`
//! camera keeps the direction and moves the origin. Mitsuba scales both offsets by
//! `1 / sqrt(spp)` before the integrator sees them; [`Camera::differentials`] takes that scale.
//! A thin lens's differentials depend on the aperture sample, which the ray does not carry:
//! none are given for it.
use super::{Camera, Projection};
use crate::math::{Norm, Ray};
use glam::Vec3;

/// The two offset rays of a camera ray (origin and direction of each).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Differentials {
    /// The ray one pixel to the right: origin, direction.
    pub x: (Vec3, Vec3),
    /// The ray one pixel down: origin, direction.
    pub y: (Vec3, Vec3),
}

impl Camera {
    /// The differentials of `ray` (a ray this camera generated), each offset scaled by
    /// `scale`; `None` for a thin lens.
    pub fn differentials(&self, ray: &Ray, scale: f32) -> Option<Differentials> {
        let (w, h) = match self.crop {
            None => (self.width, self.height),
            Some(c) => (c.film_width, c.film_height),
        };
        let tf = &self.to_world;
        match &self.projection {
            Projection::Perspective(p) => {
                // The direction at depth 1 in camera space, moved by one pixel of the film.
                let local = tf.inv.transform_vector3(ray.d);
                let local = local / local.z;
                let half = p.half_extent();
                let step = |dx: Vec3| {
                    let d = tf.vector((local + dx).unit()).unit();
                    (ray.o, ray.d + (d - ray.d) * scale)
                };
                Some(Differentials {
                    x: step(Vec3::new(-2.0 * half.x / w as f32, 0.0, 0.0)),
                    y: step(Vec3::new(0.0, -2.0 * half.y / h as f32, 0.0)),
                })
            }
            Projection::Orthographic(_) => {
                // The view is 2 wide and 2 h / w high: a pixel is 2 / w either way.
                let step = 2.0 / w as f32;
                let dx = tf.vector(Vec3::new(-step, 0.0, 0.0));
                let dy = tf.vector(Vec3::new(0.0, -step, 0.0));
                Some(Differentials {
                    x: (ray.o + dx * scale, ray.d),
                    y: (ray.o + dy * scale, ray.d),
                })
            }
            Projection::ThinLens(_) => None,
        }
    }
}

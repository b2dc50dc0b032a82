//! Mitsuba 3's `thinlens` sensor: the pinhole projection seen through an ideal thin lens of
//! radius `aperture_radius` focused at `focus_distance`. A camera ray starts at a point of the
//! aperture disk (drawn uniformly with the concentric map, as Mitsuba 3 draws it) and passes
//! through the point at depth `focus_distance` that the pinhole ray of the same film position
//! reaches, so the plane `z = focus_distance` is sharp and a point at depth `z` is spread over
//! a disk of radius `aperture_radius * |z - focus_distance| / focus_distance` on that plane.
use super::perspective::Perspective;
use crate::math::{Norm, Ray, Transform};
use crate::sampling::warp::square_to_uniform_disk_concentric;
use glam::{Vec2, Vec3};

/// A thin lens in front of a pinhole projection.
#[derive(Clone, Debug)]
pub struct ThinLens {
    /// The projection of the lens's centre.
    pub pinhole: Perspective,
    /// Radius of the aperture, in camera-space units.
    pub aperture_radius: f32,
    /// Distance along the view axis to the plane in focus.
    pub focus_distance: f32,
}

impl ThinLens {
    /// The ray, in world space, through film position `pos` of a `width` x `height` film and
    /// the point of the aperture that `lens` (in `[0,1)^2`) maps to.
    #[inline]
    pub fn generate_ray(
        &self,
        to_world: &Transform,
        pos: Vec2,
        (width, height): (u32, u32),
        lens: Vec2,
    ) -> Ray {
        let focus = self.pinhole.image_point(pos, width, height) * self.focus_distance;
        let a = square_to_uniform_disk_concentric(lens) * self.aperture_radius;
        let aperture = Vec3::new(a.x, a.y, 0.0);
        let local = (focus - aperture).unit();
        let d = to_world.vector(local).unit();
        // Distances along the ray to the clip planes z = near and z = far.
        let inv_z = 1.0 / local.z;
        let (near_t, far_t) = (self.pinhole.near * inv_z, self.pinhole.far * inv_z);
        Ray {
            o: to_world.point(aperture) + d * near_t,
            d,
            t_max: far_t - near_t,
        }
    }
}

//! Analytic disk: the unit disk in the local z = 0 plane, normal +z, placed by `to_world`.
//!
//! Scene parameters (`<shape type="disk">`): `to_world` (transform, default identity; any
//! invertible affine map, so an ellipse is fine), `flip_normals` (boolean, default false).
use crate::math::{gamma, Norm, Ray, Transform, PI};
use crate::sampling::warp::square_to_uniform_disk_concentric;
use glam::{Vec2, Vec3};

/// A disk (or ellipse) given by the image of the unit disk under an affine transform.
#[derive(Clone, Copy, Debug)]
pub struct Disk {
    /// Local to world.
    pub to_world: Transform,
    /// Unit geometric normal in world space (before `flip_normals`).
    pub normal: Vec3,
    /// World-space area.
    pub area: f32,
}

impl Disk {
    /// A disk from its transform; `None` if the transform is singular or flattens the disk.
    pub fn new(to_world: Transform) -> Option<Self> {
        let ex = to_world.vector(Vec3::X);
        let ey = to_world.vector(Vec3::Y);
        let area = PI * ex.cross(ey).norm();
        let normal = to_world.normal(Vec3::Z).unit();
        (area > 0.0 && area.is_finite() && normal.is_finite()).then_some(Disk {
            to_world,
            normal,
            area,
        })
    }

    /// Nearest intersection in `(0, t_max)`; returns `t` and the local hit point `(x, y)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
        let o = self.to_world.inv.transform_point3(ray.o);
        let d = self.to_world.inv.transform_vector3(ray.d);
        if d.z == 0.0 {
            return None;
        }
        let t = -o.z / d.z;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let x = o.x + t * d.x;
        let y = o.y + t * d.y;
        if x * x + y * y > 1.0 {
            return None;
        }
        Some((t, Vec2::new(x, y)))
    }

    /// World point and its error bound for the local point `(x, y, 0)`.
    #[inline]
    pub fn point(&self, local: Vec2) -> (Vec3, Vec3) {
        let l = Vec3::new(local.x, local.y, 0.0);
        let p = self.to_world.point(l);
        let m = self.to_world.m;
        let abs_lin = m.x_axis.truncate().abs() * l.x.abs() + m.y_axis.truncate().abs() * l.y.abs();
        let err = (abs_lin + m.w_axis.truncate().abs()) * gamma(3);
        (p, err)
    }

    /// Uniform point by area: world point, its error bound.
    pub fn sample(&self, u: Vec2) -> (Vec3, Vec3) {
        self.point(square_to_uniform_disk_concentric(u))
    }
}

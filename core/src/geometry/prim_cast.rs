//! A primitive's bounds and ray test, as the BVH's build and leaf loop call them. They live
//! apart from the primitive's record (`prim.rs`) because a cylinder's geometry is its shape's,
//! so they read the scene's shape table, and a shape's hit reads the primitive record.
use super::{Disk, Prim, Shape, ShapeKind, TriRay};
use crate::math::{Aabb, Ray};
use glam::Vec3;

impl Prim {
    /// Bounding box; `v` is the triangle's corners (ignored for other primitives). An
    /// instance's box is the scene's to compute (empty here).
    pub fn bounds(&self, v: &[Vec3; 3], disks: &[Disk], shapes: &[Shape]) -> Aabb {
        match self {
            Prim::Triangle { .. } => Aabb::point(v[0]).grow(v[1]).grow(v[2]),
            Prim::Sphere { sphere, .. } => {
                let r = Vec3::splat(sphere.radius);
                Aabb {
                    min: sphere.center - r,
                    max: sphere.center + r,
                }
            }
            Prim::Disk { disk, .. } => {
                let d = &disks[*disk as usize];
                let mut b = Aabb::EMPTY;
                for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
                    b = b.grow(d.to_world.point(Vec3::new(x, y, 0.0)));
                }
                b
            }
            Prim::Cylinder { shape } => match &shapes[*shape as usize].kind {
                ShapeKind::Cylinder(c) => c.bounds(),
                _ => Aabb::EMPTY,
            },
            Prim::Curve { shape, segment } => match &shapes[*shape as usize].kind {
                ShapeKind::Curve(c) => c.bounds(*segment as usize),
                _ => Aabb::EMPTY,
            },
            Prim::Instance { .. } => Aabb::EMPTY,
        }
    }
    /// Intersection in `(0, t_max)`: `(t, uv)`. `v` is the triangle's corners (ignored for
    /// other primitives) and `tri` the triangle test's per-ray part (`TriRay::new(ray)`).
    /// An instance gives `None`: the scene tests it.
    #[inline(always)]
    pub fn intersect(
        &self,
        ray: &Ray,
        tri: &TriRay,
        v: &[Vec3; 3],
        t_max: f32,
        disks: &[Disk],
        shapes: &[Shape],
    ) -> Option<(f32, glam::Vec2)> {
        match self {
            Prim::Triangle { .. } => tri
                .intersect(t_max, v[0], v[1], v[2])
                .map(|(t, _, b1, b2)| (t, glam::Vec2::new(b1, b2))),
            Prim::Sphere { sphere, .. } => {
                sphere.intersect(ray, t_max).map(|t| (t, glam::Vec2::ZERO))
            }
            Prim::Disk { disk, .. } => disks[*disk as usize].intersect(ray, t_max),
            Prim::Cylinder { shape } => match &shapes[*shape as usize].kind {
                ShapeKind::Cylinder(c) => c.intersect(ray, t_max).map(|t| (t, glam::Vec2::ZERO)),
                _ => None,
            },
            Prim::Curve { shape, segment } => match &shapes[*shape as usize].kind {
                ShapeKind::Curve(c) => c
                    .intersect(*segment as usize, ray, t_max)
                    .map(|(t, v)| (t, glam::Vec2::new(v, 0.0))),
                _ => None,
            },
            Prim::Instance { .. } => None,
        }
    }
}

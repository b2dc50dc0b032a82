//! Primitives as the BVH stores them: which shape (and face) each is. A triangle's corners are
//! kept apart, in blocks of four in the same order (`Scene::blocks`), so the
//! leaf loop reads 37 bytes per triangle and nothing else.
use super::{Disk, Shape, ShapeKind, Sphere, TriRay};
use crate::math::{Aabb, Ray};
use glam::Vec3;

/// One intersectable primitive, referring back to the shape it belongs to.
#[derive(Clone, Copy, Debug)]
pub enum Prim {
    /// A triangle of a mesh (its corners are in the scene's `blocks`).
    Triangle {
        /// The mesh shape's index.
        shape: u32,
        /// The triangle's index in the mesh.
        face: u32,
    },
    /// A sphere shape.
    Sphere {
        /// Its geometry.
        sphere: Sphere,
        /// The shape's index.
        shape: u32,
    },
    /// A disk shape.
    Disk {
        /// Index into the scene's disks.
        disk: u32,
        /// The shape's index.
        shape: u32,
    },
    /// A cylinder shape (its geometry is the shape's `ShapeKind::Cylinder`).
    Cylinder {
        /// The shape's index.
        shape: u32,
    },
    /// An instance of a shape group (top level only; the scene tests it through the group's
    /// own hierarchy).
    Instance {
        /// Index into the scene's instances.
        instance: u32,
    },
}

/// The closest hit found by a traversal.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Ray parameter.
    pub t: f32,
    /// Index into the scene's primitive array.
    pub prim: u32,
    /// Barycentrics (triangles) or the local disk point.
    pub uv: glam::Vec2,
}

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
            Prim::Instance { .. } => Aabb::EMPTY,
        }
    }
    /// Shape index (`u32::MAX` for an instance, which is no shape: its hit is on one of its
    /// group's shapes).
    pub fn shape(&self) -> u32 {
        match *self {
            Prim::Triangle { shape, .. }
            | Prim::Sphere { shape, .. }
            | Prim::Disk { shape, .. }
            | Prim::Cylinder { shape } => shape,
            Prim::Instance { .. } => u32::MAX,
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
            Prim::Instance { .. } => None,
        }
    }
}

//! Primitives as the BVH stores them: which shape (and face) each is. A triangle's corners are
//! kept apart, in blocks of four in the same order (`Scene::blocks`), so the
//! leaf loop reads 37 bytes per triangle and nothing else.
use super::Sphere;

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
    /// One segment of a curve shape (its geometry is the shape's `ShapeKind::Curve`).
    Curve {
        /// The shape's index.
        shape: u32,
        /// The segment's index in the curve.
        segment: u32,
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
    /// Barycentrics (triangles), the local disk point, or a curve's local parameter (x).
    pub uv: glam::Vec2,
}

impl Prim {
    /// Shape index (`u32::MAX` for an instance, which is no shape: its hit is on one of its
    /// group's shapes).
    pub fn shape(&self) -> u32 {
        match *self {
            Prim::Triangle { shape, .. }
            | Prim::Sphere { shape, .. }
            | Prim::Disk { shape, .. }
            | Prim::Cylinder { shape }
            | Prim::Curve { shape, .. } => shape,
            Prim::Instance { .. } => u32::MAX,
        }
    }
}

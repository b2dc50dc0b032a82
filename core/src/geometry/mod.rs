//! Shapes, their intersection routines, and surface sampling.
mod disk;
mod interaction;
mod mesh;
mod prim;
mod shape;
mod sphere;
mod triangle;

pub use disk::Disk;
pub use interaction::{Interaction, SHADOW_EPSILON};
pub use mesh::{interpolate_point, Mesh, TriangleHit};
pub use prim::{Hit, Prim};
pub use shape::{area_to_solid_angle, PositionSample, SampleToward, Shape, ShapeKind};
pub use sphere::{ConeSample, Sphere};
pub use triangle::{intersect_triangle, TriRay};

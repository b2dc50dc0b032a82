//! Shapes, their intersection routines, and surface sampling.
mod cylinder;
mod disk;
mod instance;
mod interaction;
mod mesh;
mod mesh_attribute;
mod mesh_site;
mod prim;
mod prim_cast;
mod shading_point;
mod shape;
mod sphere;
mod triangle;

pub use cylinder::Cylinder;
pub use disk::Disk;
pub use instance::Instance;
pub use interaction::{Interaction, SHADOW_EPSILON};
pub use mesh::{interpolate_point, Mesh, TriangleHit};
pub use mesh_attribute::MeshAttribute;
pub use mesh_site::MeshSite;
pub use prim::{Hit, Prim};
pub use shading_point::{Partials, ShadingPoint};
pub use shape::{PositionSample, SampleToward, Shape, ShapeKind};
pub use sphere::{ConeSample, Sphere};
pub use triangle::{intersect_triangle, TriRay};

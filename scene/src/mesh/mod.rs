//! Triangle mesh sources: OBJ (with MTL materials), PLY and Mitsuba `.serialized` files, and
//! Mitsuba's built-in `rectangle` and `cube`.
mod builtin;
pub mod curve_file;
mod data;
mod file_cache;
pub mod mtl;
mod mtl_material;
mod obj;
mod obj_locate;
mod ply;
mod ply_attributes;
mod ply_locate;
mod serialized;

pub use builtin::{cube, rectangle};
pub use data::{MeshData, MAX_MESH_BYTES};
pub(crate) use file_cache::{read_shared, Plan, ReadKey};
pub(crate) use mtl_material::{mtl_bsdf, MtlBsdf};
pub use obj::{load_obj, load_obj_with_materials, ObjParts};
pub use ply::load_ply;
pub(crate) use serialized::load_serialized;
pub use serialized::parse_serialized;

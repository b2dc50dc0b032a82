//! Triangle mesh sources: OBJ (with MTL materials), PLY and Mitsuba `.serialized` files, and
//! Mitsuba's built-in `rectangle` and `cube`.
mod builtin;
mod data;
pub mod mtl;
mod mtl_material;
mod obj;
mod obj_locate;
mod ply;
mod ply_locate;
mod serialized;

pub use builtin::{cube, rectangle};
pub use data::{read_mesh_bytes, MeshData, MAX_MESH_BYTES};
pub use mtl_material::{mtl_bsdf, MtlBsdf};
pub use obj::{load_obj, load_obj_with_materials, ObjParts};
pub use ply::load_ply;
pub use serialized::{load_serialized, parse_serialized};

use crate::error::InputError;
use std::path::Path;

/// Reads a mesh file by extension (`.obj`, `.ply`, `.serialized`: its first shape).
pub fn load_mesh_file(path: &Path) -> Result<MeshData, InputError> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("obj") => load_obj(path),
        Some("ply") => load_ply(path),
        Some("serialized") => load_serialized(path, 0),
        _ => Err(InputError::file(
            path,
            "unknown mesh format (use .obj, .ply or .serialized)",
        )),
    }
}

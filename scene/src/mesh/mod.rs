//! Triangle mesh sources: OBJ (with MTL materials) and PLY files, and Mitsuba's built-in
//! `rectangle` and `cube`.
mod builtin;
mod data;
pub mod mtl;
mod mtl_material;
mod obj;
mod obj_locate;
mod ply;
mod ply_locate;

pub use builtin::{cube, rectangle};
pub use data::{read_mesh_bytes, MeshData, MAX_MESH_BYTES};
pub use mtl_material::{mtl_bsdf, MtlBsdf};
pub use obj::{load_obj, load_obj_with_materials, ObjParts};
pub use ply::load_ply;

use crate::error::InputError;
use std::path::Path;

/// Reads a mesh file by extension (`.obj`, `.ply`).
pub fn load_mesh_file(path: &Path) -> Result<MeshData, InputError> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("obj") => load_obj(path),
        Some("ply") => load_ply(path),
        _ => Err(InputError::file(
            path,
            "unknown mesh format (use .obj or .ply)",
        )),
    }
}

//! Wavefront OBJ meshes, read with `tobj` (polygons fan-triangulated, one index per vertex).
//!
//! Scene parameters (`<shape type="obj">`): `filename` (string, required), `to_world` (transform),
//! `face_normals` (boolean, default false: use the file's vertex normals, or smooth ones computed
//! from the faces when the file has none), `flip_normals` (boolean, default false). All objects
//! and groups of the file form one mesh.
use super::{obj_locate::locate_obj_error, MeshData};
use crate::error::InputError;
use std::path::Path;

/// Largest OBJ file accepted (a mistake, not a mesh, beyond this).
const MAX_BYTES: u64 = 4 << 30;

/// Loads an OBJ file.
pub fn load_obj(path: &Path) -> Result<MeshData, InputError> {
    let meta = std::fs::metadata(path)
        .map_err(|e| InputError::file(path, format!("cannot read mesh: {e}")))?;
    if meta.len() > MAX_BYTES {
        return Err(InputError::file(
            path,
            format!(
                "mesh file is {} bytes, over the {MAX_BYTES} limit",
                meta.len()
            ),
        ));
    }
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let (models, _materials) = match tobj::load_obj(path, &opts) {
        Ok(r) => r,
        Err(e) => {
            return Err(locate_obj_error(path)
                .unwrap_or_else(|| InputError::file(path, format!("bad OBJ file: {e}"))))
        }
    };
    let mut data = MeshData::default();
    let with_normals = models.iter().all(|m| !m.mesh.normals.is_empty()) && !models.is_empty();
    let with_uvs = models.iter().all(|m| !m.mesh.texcoords.is_empty()) && !models.is_empty();
    for m in &models {
        let base = data.positions.len() as u64;
        let mesh = &m.mesh;
        data.positions
            .extend(mesh.positions.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        if with_normals {
            data.normals
                .extend(mesh.normals.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        }
        if with_uvs {
            // OBJ's v axis points up the image; Mitsuba 3 flips it (measured), and so do we.
            data.uvs
                .extend(mesh.texcoords.chunks_exact(2).map(|c| [c[0], 1.0 - c[1]]));
        }
        for t in mesh.indices.chunks_exact(3) {
            let idx = [base + t[0] as u64, base + t[1] as u64, base + t[2] as u64];
            if idx.iter().any(|&i| i > u32::MAX as u64) {
                return Err(InputError::file(path, "mesh has more than 2^32 vertices"));
            }
            data.indices.push(idx.map(|i| i as u32));
        }
    }
    let finite = data
        .positions
        .iter()
        .flatten()
        .chain(data.normals.iter().flatten())
        .chain(data.uvs.iter().flatten())
        .all(|v| v.is_finite());
    if !finite {
        return Err(locate_obj_error(path)
            .unwrap_or_else(|| InputError::file(path, "mesh has a non-finite number")));
    }
    data.validate(path)?;
    Ok(data)
}

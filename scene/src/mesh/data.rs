//! Mesh data in object space as every mesh reader returns it, validated, and the checked read
//! of a mesh file's bytes that every reader starts from.
use crate::error::InputError;
use std::io::Read;
use std::path::Path;
use tessera_core::geometry::MeshAttribute;
use tessera_core::math::Norm;

/// Largest mesh file accepted (4 GiB: a mistake, not a mesh, beyond this).
pub const MAX_MESH_BYTES: u64 = 4 << 30;

/// Reads a whole mesh file. Refuses what is not a regular file (a directory, `/dev/zero`, a
/// pipe) and anything over [`MAX_MESH_BYTES`], checking the size before reading and while
/// reading (a file that grows cannot make it read more).
pub(crate) fn read_mesh_bytes(path: &Path) -> Result<Vec<u8>, InputError> {
    let err = |m: String| InputError::file(path, m);
    let f = std::fs::File::open(path).map_err(|e| err(format!("cannot read mesh: {e}")))?;
    let meta = f
        .metadata()
        .map_err(|e| err(format!("cannot read mesh: {e}")))?;
    if !meta.is_file() {
        return Err(err("cannot read mesh: not a regular file".into()));
    }
    let too_big = |n: u64| {
        err(format!(
            "mesh file is {n} bytes, over the {MAX_MESH_BYTES} limit"
        ))
    };
    if meta.len() > MAX_MESH_BYTES {
        return Err(too_big(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    f.take(MAX_MESH_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| err(format!("cannot read mesh: {e}")))?;
    if bytes.len() as u64 > MAX_MESH_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Mesh data in object space, validated: indices in range, every number finite.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Vertex normals (one per position) or empty.
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates (one per position) or empty.
    pub uvs: Vec<[f32; 2]>,
    /// Triangles.
    pub indices: Vec<[u32; 3]>,
    /// The mesh attributes Mitsuba 3 makes of the file's other properties (see
    /// `ply_attributes.rs`), face attributes with one row per triangle: a mesh with any is one
    /// Mitsuba joins to no other.
    pub attributes: Vec<MeshAttribute>,
}

impl MeshData {
    /// Checks that attribute arrays match and indices are in range.
    pub fn validate(&self, path: &Path) -> Result<(), InputError> {
        let n = self.positions.len();
        if !self.normals.is_empty() && self.normals.len() != n {
            return Err(InputError::file(
                path,
                "vertex normals do not match the positions",
            ));
        }
        if !self.uvs.is_empty() && self.uvs.len() != n {
            return Err(InputError::file(
                path,
                "texture coordinates do not match the positions",
            ));
        }
        if let Some((f, _)) = self
            .indices
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&i| i as usize >= n))
        {
            return Err(InputError::file(
                path,
                format!("face {f} refers to a vertex beyond the {n} there are"),
            ));
        }
        Ok(())
    }

    /// Smooth vertex normals: the average of the normals of the faces around each vertex, each
    /// weighted by the face's angle at that vertex (what Mitsuba 3 computes when a file has none
    /// and `face_normals` is false; measured against it).
    pub(crate) fn compute_vertex_normals(&mut self) {
        use glam::Vec3;
        let mut acc = vec![Vec3::ZERO; self.positions.len()];
        for t in &self.indices {
            let p = t.map(|i| Vec3::from(self.positions[i as usize]));
            let n = (p[1] - p[0]).cross(p[2] - p[0]).unit_or_zero();
            if n == Vec3::ZERO {
                continue;
            }
            for k in 0..3 {
                let e1 = (p[(k + 1) % 3] - p[k]).unit_or_zero();
                let e2 = (p[(k + 2) % 3] - p[k]).unit_or_zero();
                let angle = e1.dot(e2).clamp(-1.0, 1.0).acos();
                acc[t[k] as usize] += n * angle;
            }
        }
        self.normals = acc.iter().map(|n| n.unit_or_zero().to_array()).collect();
    }
}

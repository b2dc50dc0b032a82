//! Values a mesh carries per vertex or per face beyond its geometry (a PLY file's colour or
//! weight properties), which the `mesh_attribute` texture reads as Mitsuba 3 does: named
//! `vertex_*` (interpolated by the hit's barycentric coordinates) or `face_*` (constant over a
//! face), with 1 to 4 components.
use alloc::string::String;
use alloc::vec::Vec;
use glam::Vec3;

/// One named attribute of a mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttribute {
    /// Mitsuba's name: `vertex_NAME` or `face_NAME`.
    pub name: String,
    /// Components per vertex or face (1 to 4).
    pub dim: usize,
    /// Per face (`face_*`, one row per triangle) rather than per vertex.
    pub per_face: bool,
    /// Row-major values, `dim` per row.
    pub values: Vec<f32>,
}

impl MeshAttribute {
    /// Row `i`'s first three components (missing ones zero).
    #[inline]
    pub(crate) fn row(&self, i: u32) -> Vec3 {
        let start = i as usize * self.dim;
        let r = &self.values[start..start + self.dim];
        Vec3::new(
            r[0],
            r.get(1).copied().unwrap_or(0.0),
            r.get(2).copied().unwrap_or(0.0),
        )
    }
}

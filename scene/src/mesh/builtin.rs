//! Mitsuba's built-in meshes.
//!
//! `<shape type="rectangle">`: the square `[-1,1]^2` in the z = 0 plane, normal +z, placed by
//! `to_world`. `<shape type="cube">`: the cube `[-1,1]^3` with outward normals (each face its own
//! four vertices, so normals are flat). Both take `to_world` and `flip_normals`.
use super::data::MeshData;

/// The unit rectangle as two triangles.
pub fn rectangle() -> MeshData {
    MeshData {
        positions: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        uvs: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        indices: vec![[0, 1, 2], [2, 3, 0]],
        attributes: Vec::new(),
    }
}

/// The unit cube as twelve triangles.
pub fn cube() -> MeshData {
    let mut m = MeshData::default();
    // For each axis and sign: the face's normal and two tangents with t1 x t2 = n.
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = [0.0f32; 3];
            n[axis] = sign;
            let mut t1 = [0.0f32; 3];
            t1[(axis + 1) % 3] = 1.0;
            let mut t2 = [0.0f32; 3];
            t2[(axis + 2) % 3] = sign;
            let base = m.positions.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                m.positions
                    .push(std::array::from_fn(|k| n[k] + a * t1[k] + b * t2[k]));
                m.normals.push(n);
                m.uvs.push([(a + 1.0) * 0.5, (b + 1.0) * 0.5]);
            }
            m.indices.push([base, base + 1, base + 2]);
            m.indices.push([base + 2, base + 3, base]);
        }
    }
    m
}

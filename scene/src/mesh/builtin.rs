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

/// The unit cube as twelve triangles, laid out as Mitsuba 3.9.1 lays it out (so that textures,
/// `prim_index` and the shading frame land where Mitsuba puts them): the faces -y, +y, +x, +z,
/// -x, -z, each with its own four vertices `4s..4s+3` (texture coordinates (0, 1), (1, 1),
/// (1, 0), (0, 0)) and the triangles `(4s, 4s+1, 4s+2)` and `(4s+3, 4s, 4s+2)`.
pub fn cube() -> MeshData {
    const FACES: [([f32; 3], [[f32; 3]; 4]); 6] = [
        (
            [0.0, -1.0, 0.0],
            [
                [1.0, -1.0, -1.0],
                [1.0, -1.0, 1.0],
                [-1.0, -1.0, 1.0],
                [-1.0, -1.0, -1.0],
            ],
        ),
        (
            [0.0, 1.0, 0.0],
            [
                [1.0, 1.0, -1.0],
                [-1.0, 1.0, -1.0],
                [-1.0, 1.0, 1.0],
                [1.0, 1.0, 1.0],
            ],
        ),
        (
            [1.0, 0.0, 0.0],
            [
                [1.0, -1.0, -1.0],
                [1.0, 1.0, -1.0],
                [1.0, 1.0, 1.0],
                [1.0, -1.0, 1.0],
            ],
        ),
        (
            [0.0, 0.0, 1.0],
            [
                [1.0, -1.0, 1.0],
                [1.0, 1.0, 1.0],
                [-1.0, 1.0, 1.0],
                [-1.0, -1.0, 1.0],
            ],
        ),
        (
            [-1.0, 0.0, 0.0],
            [
                [-1.0, -1.0, 1.0],
                [-1.0, 1.0, 1.0],
                [-1.0, 1.0, -1.0],
                [-1.0, -1.0, -1.0],
            ],
        ),
        (
            [0.0, 0.0, -1.0],
            [
                [1.0, 1.0, -1.0],
                [1.0, -1.0, -1.0],
                [-1.0, -1.0, -1.0],
                [-1.0, 1.0, -1.0],
            ],
        ),
    ];
    const UVS: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let mut m = MeshData::default();
    for (n, corners) in FACES {
        let v = m.positions.len() as u32;
        m.positions.extend_from_slice(&corners);
        m.normals.extend_from_slice(&[n; 4]);
        m.uvs.extend_from_slice(&UVS);
        m.indices.push([v, v + 1, v + 2]);
        m.indices.push([v + 3, v, v + 2]);
    }
    m
}

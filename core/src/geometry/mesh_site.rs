//! Where a ray hit a mesh (the triangle and barycentric coordinates), and the mesh
//! attributes there: what a `mesh_attribute` texture reads (`crate::texture`).
use super::Mesh;
use glam::{Vec2, Vec3};

/// Where on which triangle of a mesh a ray hit, for attribute lookups.
#[derive(Clone, Copy, Debug)]
pub struct MeshSite<'a> {
    /// The mesh hit.
    pub mesh: &'a Mesh,
    /// The triangle.
    pub face: u32,
    /// Barycentric coordinates of the second and third corners.
    pub b: Vec2,
}

impl PartialEq for MeshSite<'_> {
    fn eq(&self, other: &Self) -> bool {
        core::ptr::eq(self.mesh, other.mesh) && self.face == other.face && self.b == other.b
    }
}

impl MeshSite<'_> {
    /// The attribute `name` here, with its component count: the three corners' values blended
    /// by the barycentric coordinates for a vertex attribute, the face's row for a face
    /// attribute (first three components). `None` when the mesh has no such attribute.
    pub fn attribute(&self, name: &str) -> Option<(usize, Vec3)> {
        let a = self.mesh.attributes.iter().find(|a| a.name == name)?;
        let value = if a.per_face {
            a.row(self.face)
        } else {
            let [i0, i1, i2] = self.mesh.indices[self.face as usize];
            let b0 = 1.0 - self.b.x - self.b.y;
            a.row(i0) * b0 + a.row(i1) * self.b.x + a.row(i2) * self.b.y
        };
        Some((a.dim, value))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::MeshAttribute;
    use alloc::vec;
    use alloc::vec::Vec;

    /// One triangle with a three-component vertex attribute (corner k holds k+1, 10(k+1),
    /// 100(k+1)) and a one-component face attribute.
    fn mesh() -> Mesh {
        let mut m = Mesh::new(
            vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            Vec::new(),
            Vec::new(),
            vec![[0, 1, 2]],
        );
        m.attributes = vec![
            MeshAttribute {
                name: "vertex_color".into(),
                dim: 3,
                per_face: false,
                values: vec![1.0, 10.0, 100.0, 2.0, 20.0, 200.0, 3.0, 30.0, 300.0],
            },
            MeshAttribute {
                name: "face_weight".into(),
                dim: 1,
                per_face: true,
                values: vec![0.25],
            },
        ];
        m
    }

    #[test]
    fn vertex_values_are_blended_by_barycentrics_and_face_values_are_constant() {
        let m = mesh();
        let at = |b1: f32, b2: f32| MeshSite {
            mesh: &m,
            face: 0,
            b: Vec2::new(b1, b2),
        };
        // Corners: b = (0, 0) is the first corner, (1, 0) the second, (0, 1) the third.
        for (b, k) in [((0.0, 0.0), 1.0), ((1.0, 0.0), 2.0), ((0.0, 1.0), 3.0)] {
            let (dim, v) = at(b.0, b.1).attribute("vertex_color").unwrap();
            assert_eq!((dim, v), (3, Vec3::new(k, 10.0 * k, 100.0 * k)));
        }
        let (_, v) = at(1.0 / 3.0, 1.0 / 3.0).attribute("vertex_color").unwrap();
        assert!((v - Vec3::new(2.0, 20.0, 200.0)).abs().max_element() < 1e-4);
        for b in [(0.0, 0.0), (0.3, 0.6), (1.0, 0.0)] {
            let (dim, v) = at(b.0, b.1).attribute("face_weight").unwrap();
            assert_eq!((dim, v.x), (1, 0.25));
        }
        assert!(at(0.2, 0.2).attribute("vertex_normal").is_none());
    }
}

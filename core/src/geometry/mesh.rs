//! Triangle meshes in world space, with optional vertex normals and texture coordinates.
//!
//! Built by the driver from `obj`, `ply`, `rectangle` and `cube` shapes (see the driver's loaders
//! for their scene parameters). Positions and normals are already transformed to world space.
use super::{MeshAttribute, Parallelogram};
use crate::math::{gamma, Frame, Norm};
use crate::sampling::{warp::square_to_uniform_triangle, Discrete1D};
use alloc::boxed::Box;
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// A triangle mesh in world space.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position, or empty.
    pub normals: Vec<Vec3>,
    /// Texture coordinates, one per position, or empty.
    pub uvs: Vec<Vec2>,
    /// Triangles as indices into `positions`.
    pub indices: Vec<[u32; 3]>,
    /// Named per-vertex or per-face values (`mesh_attribute` textures read them); checked by
    /// the loader to have one row per vertex or per triangle.
    pub attributes: Vec<MeshAttribute>,
    /// Triangles chosen by area (None when the mesh has no area).
    area_dist: Option<Discrete1D>,
    /// Unit geometric normal of each triangle (zero when degenerate), computed once: every hit
    /// and every light sample on the mesh needs it.
    face_normals: Vec<Vec3>,
    /// `1 / area()`, the density of [`Mesh::sample`] by area.
    inv_area: f32,
    /// For a mesh without vertex normals, whose shading frame is constant over each triangle:
    /// the frame's first tangent per triangle (`Frame::tangent(face normal, dpdu)`, zero where
    /// that is degenerate), computed once. Empty otherwise.
    flat_tangents: Vec<Vec3>,
    /// The parallelogram the mesh is, when it is one (a `rectangle`): area sampling then maps
    /// the unit square onto it directly.
    parallelogram: Option<Box<Parallelogram>>,
}

/// What shading needs of a point on a triangle (see [`Mesh::hit`]).
#[derive(Clone, Copy, Debug)]
pub struct TriangleHit {
    /// The point.
    pub p: Vec3,
    /// Its absolute error bound, per component.
    pub p_err: Vec3,
    /// Unit geometric normal (zero for a degenerate triangle).
    pub ng: Vec3,
    /// Unit shading normal (interpolated vertex normals, else `ng`).
    pub ns: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Derivative of position along u (see [`Mesh::dpdu`]).
    pub dpdu: Vec3,
    /// `Frame::tangent(ns, dpdu)`, when the mesh has it stored (no vertex normals, so `ns` is
    /// `ng`, and a non-degenerate `dpdu`); `None` means: compute the frame from `ns` and `dpdu`.
    pub tangent: Option<Vec3>,
}

impl Mesh {
    /// Builds the mesh; indices must be in range (the loaders check and report).
    pub fn new(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        uvs: Vec<Vec2>,
        indices: Vec<[u32; 3]>,
    ) -> Self {
        let mut m = Mesh {
            positions,
            normals,
            uvs,
            indices,
            attributes: Vec::new(),
            area_dist: None,
            face_normals: Vec::new(),
            inv_area: 0.0,
            flat_tangents: Vec::new(),
            parallelogram: None,
        };
        m.area_dist = Discrete1D::new((0..m.indices.len()).map(|i| m.triangle_area(i)));
        m.face_normals = (0..m.indices.len())
            .map(|i| {
                let [a, b, c] = m.vertices(i);
                (b - a).cross(c - a).unit_or_zero()
            })
            .collect();
        m.inv_area = 1.0 / m.area();
        if m.normals.is_empty() {
            m.flat_tangents = (0..m.indices.len())
                .map(|i| {
                    let (idx, p) = m.corners(i);
                    Frame::tangent(m.face_normals[i], m.dpdu_of(idx, p)).unwrap_or(Vec3::ZERO)
                })
                .collect();
        }
        m.parallelogram =
            Parallelogram::of(&m.positions, &m.normals, &m.indices, &m.face_normals).map(Box::new);
        m
    }
    /// The parallelogram this mesh is, if it is one (see [`Parallelogram`]).
    #[inline]
    pub fn parallelogram(&self) -> Option<&Parallelogram> {
        self.parallelogram.as_deref()
    }
    /// The three corners of triangle `i`.
    #[inline]
    pub fn vertices(&self, i: usize) -> [Vec3; 3] {
        let [a, b, c] = self.indices[i];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }
    /// Area of triangle `i`.
    pub(crate) fn triangle_area(&self, i: usize) -> f32 {
        let [a, b, c] = self.vertices(i);
        0.5 * (b - a).cross(c - a).norm()
    }
    /// Total area.
    pub fn area(&self) -> f32 {
        self.area_dist.as_ref().map_or(0.0, |d| d.total() as f32)
    }
    /// `1 / area()` (infinite for a mesh without area).
    #[inline]
    pub(crate) fn inv_area(&self) -> f32 {
        self.inv_area
    }
    /// Unit geometric normal of triangle `i` (`cross(p1 - p0, p2 - p0)`, so counter-clockwise
    /// winding faces the viewer), or zero for a degenerate triangle.
    #[inline]
    pub fn face_normal(&self, i: usize) -> Vec3 {
        self.face_normals[i]
    }
    /// Surface point, its error bound, geometric normal, shading normal and uv at barycentrics.
    pub fn surface(&self, i: usize, b1: f32, b2: f32) -> (Vec3, Vec3, Vec3, Vec3, Vec2) {
        let (idx, [p0, p1, p2]) = self.corners(i);
        let (p, err) = interpolate_point(p0, p1, p2, b1, b2);
        let ng = self.face_normals[i];
        (
            p,
            err,
            ng,
            self.shading_normal(idx, ng, b1, b2),
            self.uv(idx, b1, b2),
        )
    }
    /// Everything `Shape::interaction` needs of a hit on triangle
    /// `i` at barycentrics `(b1, b2)`, reading the triangle once: [`Mesh::surface`] and
    /// [`Mesh::dpdu`] together.
    #[inline]
    pub fn hit(&self, i: usize, b1: f32, b2: f32) -> TriangleHit {
        let (idx, [p0, p1, p2]) = self.corners(i);
        let (p, p_err) = interpolate_point(p0, p1, p2, b1, b2);
        let ng = self.face_normals[i];
        TriangleHit {
            p,
            p_err,
            ng,
            ns: self.shading_normal(idx, ng, b1, b2),
            uv: self.uv(idx, b1, b2),
            dpdu: self.dpdu_of(idx, [p0, p1, p2]),
            tangent: self
                .flat_tangents
                .get(i)
                .copied()
                .filter(|s| *s != Vec3::ZERO),
        }
    }
    /// Point on triangle `i` at barycentrics `(b1, b2)`, its error bound and the unit geometric
    /// and shading normals (what light sampling needs: no uv).
    #[inline]
    pub fn point(&self, i: usize, b1: f32, b2: f32) -> (Vec3, Vec3, Vec3, Vec3) {
        let (idx, [p0, p1, p2]) = self.corners(i);
        let (p, err) = interpolate_point(p0, p1, p2, b1, b2);
        let ng = self.face_normals[i];
        (p, err, ng, self.shading_normal(idx, ng, b1, b2))
    }
    /// Texture coordinates on triangle `i` at barycentrics `(b1, b2)` (as [`Mesh::hit`] finds
    /// them).
    #[inline]
    pub(crate) fn uv_at(&self, i: usize, b1: f32, b2: f32) -> Vec2 {
        let (idx, _) = self.corners(i);
        self.uv(idx, b1, b2)
    }
    /// Derivative of position along u on triangle `i`: from the texture coordinates, or, for a
    /// mesh without them, from the implicit (0,0), (1,0), (0,1) of Mitsuba 3 (`p1 - p0`). Zero
    /// where the uv map is degenerate.
    pub fn dpdu(&self, i: usize) -> Vec3 {
        let (idx, p) = self.corners(i);
        self.dpdu_of(idx, p)
    }
    /// Mitsuba 3's position partials `(dp/du, dp/dv)` on triangle `i`: solved from the texture
    /// coordinates (both zero where their map is degenerate), or the edges `p1 - p0`,
    /// `p2 - p0` without them.
    pub fn partials(&self, i: usize) -> (Vec3, Vec3) {
        let ([i0, i1, i2], [p0, p1, p2]) = self.corners(i);
        let (e1, e2) = (p1 - p0, p2 - p0);
        if self.uvs.is_empty() {
            return (e1, e2);
        }
        let (d0, d1) = (self.uvs[i1] - self.uvs[i0], self.uvs[i2] - self.uvs[i0]);
        let det = d0.x * d1.y - d0.y * d1.x;
        if det == 0.0 || !det.is_finite() {
            return (Vec3::ZERO, Vec3::ZERO);
        }
        ((e1 * d1.y - e2 * d0.y) / det, (e2 * d0.x - e1 * d1.x) / det)
    }
    /// Vertex indices and positions of triangle `i`.
    #[inline]
    fn corners(&self, i: usize) -> ([usize; 3], [Vec3; 3]) {
        let [i0, i1, i2] = self.indices[i];
        let idx = [i0 as usize, i1 as usize, i2 as usize];
        let p = [
            self.positions[idx[0]],
            self.positions[idx[1]],
            self.positions[idx[2]],
        ];
        (idx, p)
    }
    #[inline]
    fn shading_normal(&self, [i0, i1, i2]: [usize; 3], ng: Vec3, b1: f32, b2: f32) -> Vec3 {
        if self.normals.is_empty() {
            return ng;
        }
        let b0 = 1.0 - b1 - b2;
        let n = self.normals[i0] * b0 + self.normals[i1] * b1 + self.normals[i2] * b2;
        let n = n.unit_or_zero();
        if n == Vec3::ZERO {
            ng
        } else {
            n
        }
    }
    #[inline]
    fn uv(&self, [i0, i1, i2]: [usize; 3], b1: f32, b2: f32) -> Vec2 {
        if self.uvs.is_empty() {
            return Vec2::new(b1, b2);
        }
        let b0 = 1.0 - b1 - b2;
        self.uvs[i0] * b0 + self.uvs[i1] * b1 + self.uvs[i2] * b2
    }
    #[inline]
    fn dpdu_of(&self, [i0, i1, i2]: [usize; 3], [p0, p1, p2]: [Vec3; 3]) -> Vec3 {
        if self.uvs.is_empty() {
            return p1 - p0;
        }
        let (d0, d1) = (self.uvs[i1] - self.uvs[i0], self.uvs[i2] - self.uvs[i0]);
        let det = d0.x * d1.y - d0.y * d1.x;
        if det == 0.0 || !det.is_finite() {
            return Vec3::ZERO;
        }
        ((p1 - p0) * d1.y - (p2 - p0) * d0.y) / det
    }
    /// Uniform point by area: triangle chosen by area, then uniform barycentrics.
    /// Returns `(triangle, b1, b2)`; `None` for a mesh without area.
    #[inline]
    pub fn sample(&self, u: Vec2) -> Option<(usize, f32, f32)> {
        let dist = self.area_dist.as_ref()?;
        let (i, ux) = dist.sample_reuse(u.x);
        let b = square_to_uniform_triangle(Vec2::new(ux, u.y));
        Some((i, b.x, b.y))
    }
}

/// The point at barycentrics `(b1, b2)` and its error bound (pbrt-v4's bound for the
/// interpolation).
#[inline]
pub fn interpolate_point(p0: Vec3, p1: Vec3, p2: Vec3, b1: f32, b2: f32) -> (Vec3, Vec3) {
    let b0 = 1.0 - b1 - b2;
    let p = p0 * b0 + p1 * b1 + p2 * b2;
    let err = ((p0 * b0).abs() + (p1 * b1).abs() + (p2 * b2).abs()) * gamma(7);
    (p, err)
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    fn bits(v: Option<Vec3>) -> Option<[u32; 3]> {
        v.map(|v| v.to_array().map(f32::to_bits))
    }

    #[test]
    fn stored_tangents_are_the_computed_ones() {
        // A flat mesh, with uvs (one triangle with a degenerate uv map, where the frame falls
        // back to from_normal) and without.
        let positions = vec![
            Vec3::new(0.3, -1.0, 2.0),
            Vec3::new(1.7, 0.2, -0.5),
            Vec3::new(-0.4, 1.1, 0.9),
            Vec3::new(2.0, 2.0, 2.5),
        ];
        let indices = vec![[0, 1, 2], [1, 3, 2], [0, 3, 1]];
        let uvs = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(2.0, 0.0),
        ];
        for (uvs, want_fallbacks) in [(uvs, 1), (Vec::new(), 0)] {
            let m = Mesh::new(positions.clone(), Vec::new(), uvs, indices.clone());
            let mut fallbacks = 0;
            for i in 0..indices.len() {
                let h = m.hit(i, 0.2, 0.3);
                let want = Frame::tangent(h.ns, h.dpdu);
                fallbacks += usize::from(want.is_none());
                assert_eq!(bits(h.tangent), bits(want), "triangle {i}");
            }
            assert_eq!(fallbacks, want_fallbacks);
        }
        // With vertex normals nothing is stored: the frame varies over the triangle.
        let normals = vec![Vec3::Z; 4];
        let m = Mesh::new(positions, normals, Vec::new(), indices);
        assert!(m.hit(0, 0.2, 0.3).tangent.is_none());
    }

    /// A rectangle (a parallelogram, `core/src/geometry/parallelogram.rs`) as the `rectangle`
    /// shape builds it, turned and moved: corners
    /// (-1,-1), (1,-1), (1,1), (-1,1) in the plane, triangles (0,1,2) and (2,3,0).
    fn rectangle(normals: bool, uvs: bool) -> Mesh {
        let m = glam::Mat3::from_rotation_x(0.7) * 1.6;
        let shift = Vec3::new(0.3, 4.0, -2.0);
        let positions = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|&(x, y)| m * Vec3::new(x, y, 0.0) + shift)
            .collect();
        let n = (m * Vec3::Z).unit();
        Mesh::new(
            positions,
            if normals { vec![n; 4] } else { vec![] },
            if uvs {
                vec![
                    Vec2::new(0.0, 0.0),
                    Vec2::new(1.0, 0.0),
                    Vec2::new(1.0, 1.0),
                    Vec2::new(0.0, 1.0),
                ]
            } else {
                vec![]
            },
            vec![[0, 1, 2], [2, 3, 0]],
        )
    }

    /// Every sampled point lies on one of the two triangles, and is reported on that triangle
    /// at its barycentrics there (found here independently, by projection), so that its
    /// texture coordinates are the mesh's; the normals are the triangle's. Its corners are the
    /// rectangle's four. With and without vertex normals and texture coordinates.
    #[test]
    fn points_lie_on_the_triangles_with_their_uv() {
        for (normals, uvs) in [(true, true), (false, true), (false, false)] {
            let mesh = rectangle(normals, uvs);
            let pg = *mesh
                .parallelogram()
                .expect("a rectangle is a parallelogram");
            let corners: vec::Vec<Vec3> = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .iter()
                .map(|&(s, t)| pg.point(Vec2::new(s, t)).p)
                .collect();
            for c in &corners {
                assert!(
                    mesh.positions.iter().any(|p| (*p - *c).norm() < 1e-5),
                    "{c}"
                );
            }
            for i in 0..64 {
                let u = Vec2::new((i % 8) as f32 / 7.0, (i / 8) as f32 / 7.0);
                let q = pg.point(u);
                let on = (0..2).find_map(|tri| {
                    let [a, b, c] = mesh.vertices(tri);
                    let (n, area) = ((b - a).cross(c - a), (b - a).cross(c - a).norm());
                    let b1 = (q.p - a).cross(c - a).dot(n) / (area * area);
                    let b2 = (b - a).cross(q.p - a).dot(n) / (area * area);
                    let inside = b1 >= -1e-5 && b2 >= -1e-5 && b1 + b2 <= 1.0 + 1e-5;
                    inside.then_some((tri, b1, b2))
                });
                let (tri, b1, b2) = on.unwrap_or_else(|| panic!("{u} -> {} off the mesh", q.p));
                let (p, _, ng, ns, uv) = mesh.surface(tri, b1, b2);
                let (.., uv_q) = mesh.surface(q.triangle, q.b1, q.b2);
                assert!((p - q.p).norm() < 1e-5);
                assert!((uv - uv_q).norm() < 1e-5, "{uv} against {uv_q} at {u}");
                assert!((ng - q.ng).norm() < 1e-6 && (ns - q.ns).norm() < 1e-6);
                assert!(q.p_err.min_element() > 0.0);
            }
        }
    }

    /// Not parallelograms: a corner moved off (control: the same mesh unmoved is one), vertex
    /// normals that differ, one triangle, three, the second triangle wound the other way.
    #[test]
    fn other_meshes_are_not_parallelograms() {
        let good = rectangle(true, true);
        assert!(good.parallelogram().is_some());
        let rebuilt = |change: &dyn Fn(&mut Mesh)| {
            let mut m = good.clone();
            change(&mut m);
            Mesh::new(m.positions, m.normals, m.uvs, m.indices)
        };
        let off = rebuilt(&|m| m.positions[3] += Vec3::new(0.0, 0.01, 0.0));
        assert!(off.parallelogram().is_none());
        let normals = rebuilt(&|m| m.normals[3] = Vec3::X);
        assert!(normals.parallelogram().is_none());
        let one = rebuilt(&|m| m.indices.truncate(1));
        assert!(one.parallelogram().is_none());
        let three = rebuilt(&|m| m.indices.push([0, 1, 3]));
        assert!(three.parallelogram().is_none());
        let flipped = rebuilt(&|m| m.indices[1] = [2, 0, 3]);
        assert!(flipped.parallelogram().is_none());
    }
}

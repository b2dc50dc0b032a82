//! A mesh that is one parallelogram (two triangles sharing a diagonal, as a `rectangle` shape
//! or an exported quad becomes), sampled by area with one affine map of the unit square.
//!
//! Light sampling on a mesh picks a triangle by area (a search in a table), then a point of it
//! (a square root), then interpolates the triangle's corners, normals and texture coordinates.
//! For the most common area light, a rectangle, all of that is one affine map: the corner plus
//! the two edges scaled by the sample. The density is the same (one over the area), so the
//! image converges to the same values; only which point a given sample lands on changes.
//!
//! A point's texture coordinates are the mesh's own at the point (the triangle it falls in and
//! its barycentrics there follow from the two coordinates), so a textured emitter reads the
//! texels it would read through the triangles. A mesh is taken for a parallelogram only when its
//! vertex normals, if any, are equal (the shading normal is then constant). How far the fourth
//! corner is from the parallelogram's (the corners rounded to floats after their transform) is
//! added to each point's error bound, so that a shadow ray aimed at the point still stops short
//! of the light's surface.
use crate::math::{gamma, Norm};
use glam::{Vec2, Vec3};

/// The parallelogram `o + s e1 + t e2` for `(s, t)` in the unit square: the first triangle is
/// `s + t <= 1` (corners `o`, `o + e1`, `o + e2`), the second the rest. With its constant
/// normals, the error bound its points carry beyond their own rounding, and where each
/// triangle keeps its corners.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parallelogram {
    o: Vec3,
    e1: Vec3,
    e2: Vec3,
    /// Absolute error bound of every point (per component): the rounding of the affine map,
    /// a few roundings of values no larger than the corners' magnitudes, plus how far the map
    /// may be from the two triangles (the fourth corner's distance from the parallelogram's).
    p_err: Vec3,
    /// Per triangle, which of the point's three weights (see [`Parallelogram::point`]) belongs
    /// to its second and third corner: its barycentrics `(b1, b2)`.
    corners: [[u8; 2]; 2],
    /// Unit geometric normal (the first triangle's).
    ng: Vec3,
    /// Unit shading normal (the vertex normal, else `ng`).
    ns: Vec3,
}

/// A point of a [`Parallelogram`]: position, its error bound, normals and texture coordinates.
#[derive(Clone, Copy, Debug)]
pub struct ParallelogramPoint {
    /// The point.
    pub p: Vec3,
    /// Its absolute error bound, per component.
    pub p_err: Vec3,
    /// Unit geometric normal.
    pub ng: Vec3,
    /// Unit shading normal.
    pub ns: Vec3,
    /// The triangle the point is on.
    pub triangle: usize,
    /// Its barycentrics there.
    pub b1: f32,
    /// Its barycentrics there.
    pub b2: f32,
}

/// Relative tolerance of the fourth corner against the parallelogram's, and of the two faces'
/// normals against each other.
const TOLERANCE: f32 = 1.0e-5;

impl Parallelogram {
    /// The parallelogram a mesh is (its vertex `positions`, vertex `normals` or none, triangle
    /// `indices`, and the unit normals of its faces), or `None`: not exactly two triangles
    /// sharing an edge, vertex normals that differ, a degenerate face, faces wound opposite
    /// ways, or a fourth corner off the parallelogram by more than a small relative tolerance.
    pub fn of(
        positions: &[Vec3],
        normals: &[Vec3],
        indices: &[[u32; 3]],
        face_normals: &[Vec3],
    ) -> Option<Parallelogram> {
        let [a, b] = indices[..] else {
            return None;
        };
        if let Some(n0) = normals.first() {
            if normals.iter().any(|n| n != n0) {
                return None;
            }
        }
        // The corner of the first triangle that the second does not share, then the shared
        // two in the first triangle's winding order.
        let k = (0..3).find(|&k| !b.contains(&a[k]))?;
        let (q0, s, t) = (a[k], a[(k + 1) % 3], a[(k + 2) % 3]);
        let q1 = *b.iter().find(|&&v| v != s && v != t)?;
        if !b.contains(&s) || !b.contains(&t) || q1 == q0 {
            return None;
        }
        let p = |i: u32| positions[i as usize];
        let (o, e1, e2) = (p(q0), p(s) - p(q0), p(t) - p(q0));
        let mismatch = (p(q1) - (p(s) + p(t) - p(q0))).abs();
        let size = e1.abs() + e2.abs();
        if !(mismatch.max_element() <= TOLERANCE * size.max_element()) {
            return None;
        }
        // Weight 0 is the corner opposite the shared edge (`q0`, `q1`), 1 is `s`'s, 2 is `t`'s.
        let code = |v: u32, q: u32| [q, s, t].iter().position(|&c| c == v).unwrap_or(0) as u8;
        let corners = [
            [code(a[1], q0), code(a[2], q0)],
            [code(b[1], q1), code(b[2], q1)],
        ];
        let [ng, ng1] = face_normals[..] else {
            return None;
        };
        // Both faces must face the same way (a quad whose triangles are wound oppositely emits
        // from each half to its own side, which one normal cannot say).
        if ng == Vec3::ZERO || ng1 == Vec3::ZERO || !(ng.dot(ng1) > 1.0 - TOLERANCE) {
            return None;
        }
        let ns = match normals.first() {
            Some(n) => match n.unit_or_zero() {
                n if n == Vec3::ZERO => ng,
                n => n,
            },
            None => ng,
        };
        let p_err = (o.abs() + p(s).abs() + p(t).abs()) * gamma(7) + mismatch;
        Some(Parallelogram {
            o,
            e1,
            e2,
            p_err,
            corners,
            ng,
            ns,
        })
    }

    /// The point at `u` in the unit square (uniform by area for uniform `u`), with the
    /// triangle it is on and its barycentrics there.
    #[inline]
    pub fn point(&self, u: Vec2) -> ParallelogramPoint {
        let p = self.o + self.e1 * u.x + self.e2 * u.y;
        // The weights of `q0`, `s`, `t` on the first triangle, of `q1`, `s`, `t` on the second.
        let (triangle, w) = if u.x + u.y <= 1.0 {
            (0, [1.0 - u.x - u.y, u.x, u.y])
        } else {
            (1, [u.x + u.y - 1.0, 1.0 - u.y, 1.0 - u.x])
        };
        let [c1, c2] = self.corners[triangle];
        ParallelogramPoint {
            p,
            p_err: self.p_err,
            ng: self.ng,
            ns: self.ns,
            triangle,
            b1: w[c1 as usize],
            b2: w[c2 as usize],
        }
    }
}

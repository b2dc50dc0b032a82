//! Orthonormal frames: local shading coordinates with the normal on +z.
use crate::math::sqrt;
use glam::Vec3;

/// An orthonormal basis `(s, t, n)`; local coordinates have `n` as +z.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent.
    pub t: Vec3,
    /// Normal.
    pub n: Vec3,
}

impl Frame {
    /// A frame around a unit normal (Duff et al. 2017, branchless and continuous but at one seam).
    pub fn from_normal(n: Vec3) -> Self {
        let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }
    /// A frame around a unit normal whose first tangent follows `dpdu` (the surface's
    /// derivative along u, projected onto the tangent plane), as Mitsuba 3 orients anisotropic
    /// materials; falls back to [`Frame::from_normal`] where `dpdu` is degenerate.
    #[inline]
    pub fn from_normal_tangent(n: Vec3, dpdu: Vec3) -> Self {
        match Frame::tangent(n, dpdu) {
            Some(s) => Frame {
                s,
                t: n.cross(s),
                n,
            },
            None => Frame::from_normal(n),
        }
    }
    /// The first tangent [`Frame::from_normal_tangent`] uses for the unit normal `n`, or `None`
    /// where `dpdu` is degenerate and it falls back to [`Frame::from_normal`].
    #[inline]
    pub fn tangent(n: Vec3, dpdu: Vec3) -> Option<Vec3> {
        let s = dpdu - n * n.dot(dpdu);
        let len2 = s.length_squared();
        if !(len2 > 1e-20 * dpdu.length_squared().max(1e-30)) || !len2.is_finite() {
            return None;
        }
        Some(s / sqrt(len2))
    }
    /// World direction to local coordinates.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }
    /// Local direction to world coordinates.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

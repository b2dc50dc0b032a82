//! Affine transforms with their inverse, for points, vectors and normals.
use glam::{Mat4, Vec3};

/// An affine transform and its inverse (kept together so normals transform correctly).
#[derive(Clone, Copy, Debug)]
pub struct Transform {
    /// Object to world.
    pub m: Mat4,
    /// World to object.
    pub inv: Mat4,
}

impl Transform {
    /// The identity.
    pub const IDENTITY: Transform = Transform {
        m: Mat4::IDENTITY,
        inv: Mat4::IDENTITY,
    };

    /// From an invertible matrix; `None` if it is singular or not finite.
    pub fn new(m: Mat4) -> Option<Self> {
        let det = m.determinant();
        if !det.is_finite() || det == 0.0 || !m.is_finite() {
            return None;
        }
        let inv = m.inverse();
        inv.is_finite().then_some(Transform { m, inv })
    }
    /// Transforms a point.
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        self.m.transform_point3(p)
    }
    /// Transforms a direction (no translation).
    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.m.transform_vector3(v)
    }
    /// Transforms a normal (inverse transpose), not normalized.
    #[inline]
    pub fn normal(&self, n: Vec3) -> Vec3 {
        self.inv.transpose().transform_vector3(n)
    }
}

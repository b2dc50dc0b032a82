//! Floating-point error bounds and the robust ray-origin offset (pbrt-v4, Pharr et al.).
//!
//! A hit point carries an absolute error bound `p_err` per component, derived from how it was
//! computed (barycentric interpolation, sphere re-projection). A new ray leaves from the point
//! pushed along the geometric normal by `dot(|n|, p_err)` and rounded away from the surface,
//! which is correct at every scene scale: no fixed epsilon.
use glam::Vec3;

/// `n eps / (1 - n eps)`, the classic bound on `n` successive rounding errors (f32).
#[inline]
pub const fn gamma(n: i32) -> f32 {
    let e = f32::EPSILON * 0.5 * n as f32;
    e / (1.0 - e)
}

/// The next representable float above `v` (unchanged for +inf and NaN).
#[inline]
pub fn next_up(v: f32) -> f32 {
    if v.is_infinite() && v > 0.0 || v.is_nan() {
        return v;
    }
    let v = if v == -0.0 { 0.0 } else { v };
    let bits = v.to_bits();
    let bits = if v >= 0.0 { bits + 1 } else { bits - 1 };
    f32::from_bits(bits)
}

/// The next representable float below `v`.
#[inline]
pub fn next_down(v: f32) -> f32 {
    -next_up(-v)
}

/// Offsets a surface point `p` with component error `p_err` so that a ray leaving in direction
/// `w` cannot re-hit the surface with geometric normal `n` it starts on.
#[inline]
pub fn offset_ray_origin(p: Vec3, p_err: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    let d = n.abs().dot(p_err);
    let mut offset = n * d;
    if w.dot(n) < 0.0 {
        offset = -offset;
    }
    let po = p + offset;
    // Round away from p so the offset is not lost to rounding.
    let r = |po: f32, off: f32| {
        if off > 0.0 {
            next_up(po)
        } else if off < 0.0 {
            next_down(po)
        } else {
            po
        }
    };
    Vec3::new(r(po.x, offset.x), r(po.y, offset.y), r(po.z, offset.z))
}

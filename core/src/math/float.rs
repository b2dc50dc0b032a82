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
    // Branch-free: which side a ray leaves on is as good as random, so the former `if` was a
    // frequent mispredict; `n * -d` has the same bits as `-(n * d)`.
    let offset = n * if w.dot(n) < 0.0 { -d } else { d };
    let po = p + offset;
    // Round away from p so the offset is not lost to rounding.
    Vec3::new(
        step_away(po.x, offset.x),
        step_away(po.y, offset.y),
        step_away(po.z, offset.z),
    )
}

/// `v` moved one representable float in the direction of `off`'s sign: [`next_up`] when `off`
/// is positive, [`next_down`] when negative, `v` itself when `off` is zero or NaN. The same
/// bits as those functions, computed with selects instead of branches (`next_down(v)` is
/// `-next_up(-v)`, and negation is a flip of the sign bit).
#[inline(always)]
fn step_away(v: f32, off: f32) -> f32 {
    let sign = off.to_bits() & 0x8000_0000;
    let y = f32::from_bits(v.to_bits() ^ sign);
    let b = y.to_bits();
    let b = if b == 0x8000_0000 { 0 } else { b };
    let stepped = if (b as i32) >= 0 {
        b.wrapping_add(1)
    } else {
        b.wrapping_sub(1)
    };
    let up = if y.is_nan() || y == f32::INFINITY {
        y
    } else {
        f32::from_bits(stepped)
    };
    let r = f32::from_bits(up.to_bits() ^ sign);
    if off != 0.0 && !off.is_nan() {
        r
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rounding step as first written, with branches.
    fn step_reference(v: f32, off: f32) -> f32 {
        if off > 0.0 {
            next_up(v)
        } else if off < 0.0 {
            next_down(v)
        } else {
            v
        }
    }

    #[test]
    fn step_away_equals_next_up_and_down() {
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::from_bits(1),
            f32::from_bits(0x8000_0001),
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
        ];
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut values: alloc::vec::Vec<f32> = special.to_vec();
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            values.push(f32::from_bits(x as u32));
        }
        let mut checked = 0;
        for &v in &values {
            for &off in &special {
                let (a, b) = (step_away(v, off), step_reference(v, off));
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "v {v:e} ({:#x}) off {off}",
                    v.to_bits()
                );
                checked += 1;
            }
        }
        assert_eq!(checked, values.len() * special.len());
        // Control: the step really moves finite values (a no-op would pass the NaN rows only).
        assert_ne!(step_away(1.0, 1.0), 1.0);
        assert!(step_away(1.0, -1.0) < 1.0);
    }
}

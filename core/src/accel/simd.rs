//! The ray-box slab test's common ground: a ray prepared once for it ([`RayPre`]), the row
//! indices of boxes stored in SoA layout, the widening of the exit distance, and the portable
//! lane-by-lane test (`hit_scalar`) whose bits the SIMD tests of [`super::simd8`] reproduce.
//!
//! The test uses IEEE subtraction and multiplication (no fused multiply-add) in a fixed order,
//! and the NaN rule of SSE's `minps`/`maxps`: when a comparison is unordered the second operand
//! is returned. The running bound is always the second operand, so a NaN slab distance (`0 *
//! inf`: the origin on a slab plane of an axis the ray is parallel to) is dropped and the slab
//! does not cull, which is conservative. No `unsafe` here: the intrinsics are in
//! [`super::simd8`].

use crate::math::{gamma, Ray};

/// Row of `min_x` in SoA boxes (`rows[MIN_X + axis][lane]`); `min_y`, `min_z` follow.
pub const MIN_X: usize = 0;
/// Row of `max_x` in SoA boxes (`rows[MAX_X + axis][lane]`); `max_y`, `max_z` follow.
pub const MAX_X: usize = 3;

/// What the slab test needs of a ray, computed once per ray.
#[derive(Clone, Copy, Debug)]
pub struct RayPre {
    /// Origin.
    pub o: [f32; 3],
    /// `1 / d` per axis (`±inf` for a zero component, by the sign of that zero).
    pub inv: [f32; 3],
    /// Per axis, the row (of SoA boxes) of the plane the ray enters by.
    pub near: [usize; 3],
    /// Per axis, the row of the plane the ray leaves by.
    pub far: [usize; 3],
}

impl RayPre {
    /// Precomputes the inverse direction and the near/far planes from its signs.
    #[inline]
    pub fn new(ray: &Ray) -> RayPre {
        let inv = [1.0 / ray.d.x, 1.0 / ray.d.y, 1.0 / ray.d.z];
        let mut near = [0; 3];
        let mut far = [0; 3];
        for a in 0..3 {
            // `1 / -0.0` is `-inf`: a negative zero direction enters by the max plane.
            let neg = inv[a] < 0.0;
            near[a] = if neg { MAX_X + a } else { MIN_X + a };
            far[a] = if neg { MIN_X + a } else { MAX_X + a };
        }
        RayPre {
            o: ray.o.to_array(),
            inv,
            near,
            far,
        }
    }
}

/// Widening of the exit distance that covers the rounding of the slab test (as pbrt-v4).
pub(super) const FAR_SCALE: f32 = 1.0 + 2.0 * gamma(3);

/// `minps` on one lane: `a` if `a < b`, else `b` (also when either is NaN).
#[inline(always)]
fn min_sse(a: f32, b: f32) -> f32 {
    if a < b {
        a
    } else {
        b
    }
}

/// `maxps` on one lane: `a` if `a > b`, else `b` (also when either is NaN).
#[inline(always)]
fn max_sse(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

/// The portable slab test on `N` boxes in SoA rows (`rows[MIN_X + axis][lane]`,
/// `rows[MAX_X + axis][lane]`): bit `i` of the mask is set when the ray meets box `i` within
/// `[0, t_max]`; `t_near[i]` is where it enters (meaningful for set bits only). Lane by lane the
/// operations of the SSE and AVX2 tests; the eight-box reference
/// ([`super::simd8::hit8_scalar`]) is this one.
#[inline]
pub(super) fn hit_scalar<const N: usize>(
    rows: &[[f32; N]; 6],
    ray: &RayPre,
    t_max: f32,
) -> (u32, [f32; N]) {
    let mut mask = 0;
    let mut t_near = [0.0f32; N];
    for (lane, tn_out) in t_near.iter_mut().enumerate() {
        let mut tn = 0.0f32;
        let mut tf = f32::INFINITY;
        for a in 0..3 {
            let t0 = (rows[ray.near[a]][lane] - ray.o[a]) * ray.inv[a];
            let t1 = (rows[ray.far[a]][lane] - ray.o[a]) * ray.inv[a];
            tn = max_sse(t0, tn);
            tf = min_sse(t1, tf);
        }
        tf = min_sse(tf * FAR_SCALE, t_max);
        *tn_out = tn;
        if tn <= tf {
            mask |= 1 << lane;
        }
    }
    (mask, t_near)
}

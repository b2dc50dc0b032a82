//! Four ray-box slab tests at once: the only module of the crate allowed `unsafe`.
//!
//! On x86_64 the test runs on SSE registers (`core::arch::x86_64`); elsewhere a scalar loop
//! computes the same bits. Both use the same operations in the same order (IEEE subtraction and
//! multiplication, no fused multiply-add) and the same NaN rule as SSE's `minps`/`maxps`: when a
//! comparison is unordered the second operand is returned. The running bound is always the
//! second operand, so a NaN slab distance (`0 * inf`: the origin on a slab plane of an axis the
//! ray is parallel to) is dropped and the slab does not cull, which is conservative.
//!
//! Why `unsafe` here: the SSE intrinsics are `unsafe fn`s unless the calling function itself is
//! declared `#[target_feature(enable = "sse")]`, and calling such a function from ordinary code
//! is `unsafe` again, even though SSE and SSE2 are part of the x86_64 baseline and statically
//! enabled. Each block below says why it is sound.
#![allow(unsafe_code)]

use crate::math::{gamma, Ray};

/// Index of each bound in [`Boxes4::b`].
pub const MIN_X: usize = 0;
/// Index of `max_x` in [`Boxes4::b`]; `max_y`, `max_z` follow.
pub const MAX_X: usize = 3;

/// Four boxes in SoA layout: `b[MIN_X + axis][lane]` and `b[MAX_X + axis][lane]`. An unused lane
/// holds the empty box (min `+inf`, max `-inf`), which no ray hits.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(16))]
pub struct Boxes4 {
    /// `[min_x, min_y, min_z, max_x, max_y, max_z]`, four lanes each.
    pub b: [[f32; 4]; 6],
}

impl Boxes4 {
    /// Four empty boxes.
    pub const EMPTY: Boxes4 = Boxes4 {
        b: [
            [f32::INFINITY; 4],
            [f32::INFINITY; 4],
            [f32::INFINITY; 4],
            [f32::NEG_INFINITY; 4],
            [f32::NEG_INFINITY; 4],
            [f32::NEG_INFINITY; 4],
        ],
    };
}

/// What the slab test needs of a ray, computed once per ray.
#[derive(Clone, Copy, Debug)]
pub struct RayPre {
    /// Origin.
    pub o: [f32; 3],
    /// `1 / d` per axis (`±inf` for a zero component, by the sign of that zero).
    pub inv: [f32; 3],
    /// Per axis, the index in [`Boxes4::b`] of the plane the ray enters by.
    pub near: [usize; 3],
    /// Per axis, the index of the plane the ray leaves by.
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

/// The portable slab test: bit `i` of the mask is set when the ray meets box `i` within
/// `[0, t_max]`; `t_near[i]` is where it enters (meaningful for set bits only). Gives exactly the
/// results of the SSE version; used where SSE is unavailable, and by tests on every target.
#[inline]
pub fn hit4_scalar(boxes: &Boxes4, ray: &RayPre, t_max: f32) -> (u32, [f32; 4]) {
    hit_scalar(&boxes.b, ray, t_max)
}

/// The portable slab test on `N` boxes in SoA rows (`rows[MIN_X + axis][lane]`,
/// `rows[MAX_X + axis][lane]`): lane by lane the operations of the SSE and AVX2 tests, so the
/// 4- and 8-wide scalar tests ([`hit4_scalar`], `simd8::hit8_scalar`) are this one.
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

/// The SSE slab test; same contract and bits as [`hit4_scalar`].
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn hit4_sse(boxes: &Boxes4, ray: &RayPre, t_max: f32) -> (u32, [f32; 4]) {
    use core::arch::x86_64::*;
    let s = FAR_SCALE;
    let mut t_near = [0.0f32; 4];
    // SAFETY: SSE and SSE2 are in the x86_64 baseline (statically enabled on every x86_64
    // target), so the intrinsics are available. The loads read `boxes.b[i]`, a `[f32; 4]`
    // borrowed for the call (four valid, initialised f32s; `loadu` needs no alignment); the store
    // writes the local `t_near`, a `[f32; 4]` exclusively borrowed here.
    let mask = unsafe {
        let mut tn = _mm_setzero_ps();
        let mut tf = _mm_set1_ps(f32::INFINITY);
        for a in 0..3 {
            let o = _mm_set1_ps(ray.o[a]);
            let inv = _mm_set1_ps(ray.inv[a]);
            let near = _mm_loadu_ps(boxes.b[ray.near[a]].as_ptr());
            let far = _mm_loadu_ps(boxes.b[ray.far[a]].as_ptr());
            let t0 = _mm_mul_ps(_mm_sub_ps(near, o), inv);
            let t1 = _mm_mul_ps(_mm_sub_ps(far, o), inv);
            tn = _mm_max_ps(t0, tn);
            tf = _mm_min_ps(t1, tf);
        }
        tf = _mm_min_ps(_mm_mul_ps(tf, _mm_set1_ps(s)), _mm_set1_ps(t_max));
        _mm_storeu_ps(t_near.as_mut_ptr(), tn);
        _mm_movemask_ps(_mm_cmple_ps(tn, tf)) as u32
    };
    (mask, t_near)
}

/// The slab test for this target: SSE on x86_64, [`hit4_scalar`] elsewhere.
#[inline(always)]
pub fn hit4(boxes: &Boxes4, ray: &RayPre, t_max: f32) -> (u32, [f32; 4]) {
    #[cfg(target_arch = "x86_64")]
    {
        hit4_sse(boxes, ray, t_max)
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        hit4_scalar(boxes, ray, t_max)
    }
}

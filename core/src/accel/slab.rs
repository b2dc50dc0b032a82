//! The ray-box slab test's common ground: a ray prepared once for it ([`RayPre`]), the row
//! indices of boxes stored in SoA layout, the widening of the exit distance, and the portable
//! lane-by-lane test (`hit_scalar`) whose bits the SIMD tests of `slab_simd` reproduce.
//!
//! The test uses IEEE subtraction and multiplication (no fused multiply-add) in a fixed order,
//! and reduces the slab distances with integer `max`/`min` on their bit patterns (`pmaxsd`,
//! `pminsd`: one cycle each, where float `maxps`/`minps` take four, and the reductions lie on
//! the path from a node's load to the next node's), then compares the two as integers.
//! - Entry: the running value starts at `+0`, so the integer order is the float order: positive
//!   floats compare as their bits do, and every negative value (`-0`, and the NaN of `0 * inf`
//!   when the origin lies on a plane of an axis the ray is parallel to, negative on x86) falls
//!   below `+0` and is dropped. The portable loop drops a NaN explicitly, whatever its sign.
//! - Exit: distances are measured from an origin at least a float behind the ray's along each axis
//!   ([`RayPre::o_far`]). An exit plane at or beyond the origin then gives a positive distance
//!   (through the origin: a tiny one, or `+inf` for a parallel axis, never `0 * inf`), and a zero
//!   or negative exit means a plane truly behind the origin. Those cull, `-0` included, which is
//!   why the integer comparison may treat `-0` as negative. The one NaN left (a parallel axis
//!   whose plane lies exactly on that moved origin) also means "behind" and culls.
//!
//! The mask keeps the float test's guarantee: it never drops a box the ray meets within
//! `[0, t_max]`. No `unsafe` here: the intrinsics are in `slab_simd`.

use crate::math::{gamma, Ray};

/// Row of `min_x` in SoA boxes (`rows[MIN_X + axis][lane]`); `min_y`, `min_z` follow.
pub const MIN_X: usize = 0;
/// Row of `max_x` in SoA boxes (`rows[MAX_X + axis][lane]`); `max_y`, `max_z` follow.
pub const MAX_X: usize = 3;

/// What the slab test needs of a ray, computed once per ray.
#[derive(Clone, Copy, Debug)]
pub struct RayPre {
    /// Origin, for entry distances.
    pub o: [f32; 3],
    /// Origin for exit distances: `o` moved back along each axis (against the sign of `inv`) by
    /// at least one float (one or two, except near zero, where the least normal float is the
    /// step), so an exit plane through the origin gives a positive distance (see the module).
    pub o_far: [f32; 3],
    /// `1 / d` per axis (`±inf` for a zero component, by the sign of that zero).
    pub inv: [f32; 3],
    /// `inv * FAR_SCALE`: the exit distances' widening folded into the inverse (the same number
    /// of roundings as widening the reduced distance).
    pub inv_far: [f32; 3],
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
        let o = ray.o.to_array();
        let mut near = [0; 3];
        let mut far = [0; 3];
        let mut o_far = o;
        for a in 0..3 {
            // `1 / -0.0` is `-inf`: a negative zero direction enters by the max plane.
            let neg = inv[a] < 0.0;
            near[a] = if neg { MAX_X + a } else { MIN_X + a };
            far[a] = if neg { MIN_X + a } else { MAX_X + a };
            // At least one float back (`|o| 2^-23` is one or two units in the last place), without
            // the branches of `next_up`/`next_down`. The least normal float covers `o = 0`; a
            // subnormal there would make every subtraction of the walk a slow microcode assist
            // (measured: camera rays from an origin with a zero coordinate ran at half speed).
            let back = o[a].abs() * f32::EPSILON + f32::MIN_POSITIVE;
            o_far[a] = o[a] - back.copysign(inv[a]);
        }
        RayPre {
            o,
            o_far,
            inv,
            inv_far: inv.map(|i| i * FAR_SCALE),
            near,
            far,
        }
    }
}

/// Widening of the exit distance that covers the rounding of the slab test (as pbrt-v4).
pub(super) const FAR_SCALE: f32 = 1.0 + 2.0 * gamma(3);

/// A float's bits as a signed integer, the order the reductions use.
#[inline(always)]
fn key(t: f32) -> i32 {
    t.to_bits() as i32
}

/// The portable slab test on `N` boxes in SoA rows (`rows[MIN_X + axis][lane]`,
/// `rows[MAX_X + axis][lane]`): bit `i` of the mask is set when the ray meets box `i` within
/// `[0, t_max]`; `t_near[i]` is where it enters (meaningful for set bits only). Lane by lane the
/// operations of the SSE and AVX2 tests; the eight-box reference
/// (`slab_simd::hit8_scalar`) is this one. NaN distances are handled explicitly (an entry
/// dropped, an exit culls), as the integer reductions handle x86's NaN, whose sign bit is set.
#[inline]
pub(super) fn hit_scalar<const N: usize>(
    rows: &[[f32; N]; 6],
    ray: &RayPre,
    t_max: f32,
) -> (u32, [f32; N]) {
    let mut mask = 0;
    let mut t_near = [0.0f32; N];
    for (lane, tn_out) in t_near.iter_mut().enumerate() {
        let mut tn = key(0.0);
        let mut tf = key(t_max);
        for a in 0..3 {
            let t0 = (rows[ray.near[a]][lane] - ray.o[a]) * ray.inv[a];
            let t1 = (rows[ray.far[a]][lane] - ray.o_far[a]) * ray.inv_far[a];
            if !t0.is_nan() {
                tn = tn.max(key(t0));
            }
            tf = tf.min(if t1.is_nan() { i32::MIN } else { key(t1) });
        }
        *tn_out = f32::from_bits(tn as u32);
        if tn <= tf {
            mask |= 1 << lane;
        }
    }
    (mask, t_near)
}

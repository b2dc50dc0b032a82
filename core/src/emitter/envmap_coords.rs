//! An environment map's image coordinates of a direction, one at a time ([`map_coords`]) or eight
//! at once ([`coords8`]): one of the crate's few modules allowed `unsafe`.
//!
//! A direction's coordinates (rotation into the map's frame, normalisation, the polynomial
//! `atan2` and `acos` of `math::arc`, the wrap into `[0, width)`) are one long chain of
//! dependent operations, the most expensive part of a lookup; a camera ray that escapes to the
//! sky does little else. Eight such chains side by side in 256-bit registers cost about what
//! one costs alone. Two versions give the same bits, those of [`map_coords`] after the same
//! rotation and normalisation as `EnvMap::eval`:
//! - [`coords8_avx2`]: the eight lanes in AVX2 registers, the same IEEE operations in the same
//!   order (no fused multiply-add), each branch of the scalar code a select; on CPUs that have
//!   AVX2, detected at run time (the [`Avx2`] token);
//! - [`coords8_portable`]: the scalar code lane by lane, for other CPUs and as the tests'
//!   reference.
//!
//! Why `unsafe` here: calling a `#[target_feature]` function from code compiled without that
//! feature is `unsafe` (the token vouches for the CPU), and so are the unaligned loads and
//! stores of the lane arrays. Each block says why it is sound.
#![allow(unsafe_code)]

use crate::accel::slab_simd::Avx2;
use crate::math::{acos, atan2, Norm, INV_PI, INV_TWO_PI};
#[cfg(test)]
use crate::Color;
use glam::{Mat3, Vec3};

/// Image coordinates `(s, v)` of a local unit direction `l` in a map `width` pixels wide: `s`
/// in `[0, width)` counts pixel centres from column 0 (the `u` of Mitsuba shifted by half a
/// pixel), `v` in `[0, 1]`. [`coords8`] computes the same bits for eight directions at a time.
#[inline]
pub(super) fn map_coords(l: Vec3, width: usize) -> (f32, f32) {
    let w = width as f32;
    let mut s = atan2(l.x, -l.z) * INV_TWO_PI * w - 0.5;
    if s < 0.0 {
        s += w;
    }
    if s < 0.0 {
        s += w;
    }
    if s >= w {
        s -= w;
    }
    let v = acos(l.y.clamp(-1.0, 1.0)) * INV_PI;
    (s, v)
}

/// Image coordinates of eight directions: lane `k` holds [`map_coords`] of direction `k`'s
/// local unit form where bit `k` of `valid` is set, and is meaningless where it is not (the
/// direction has no unit form: zero, too small or not finite; the map is black there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Coords8 {
    /// Column coordinate of each lane, in `[0, width)`.
    pub s: [f32; 8],
    /// Row coordinate of each lane, in `[0, 1]`.
    pub v: [f32; 8],
    /// Bit `k` set where lane `k`'s direction has a unit form.
    pub valid: u32,
}

/// [`Coords8`] of the world directions `d`, rotated by `to_local` into a map `width` pixels
/// wide, with AVX2 when `avx2` is given (the same bits either way).
#[inline]
pub(super) fn coords8(avx2: Option<Avx2>, to_local: &Mat3, width: usize, d: &[Vec3; 8]) -> Coords8 {
    match avx2 {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: the token exists only when `Avx2::detect` found AVX2 usable on this CPU.
        Some(_) => unsafe { coords8_avx2(to_local, width, d) },
        _ => coords8_portable(to_local, width, d),
    }
}

/// [`coords8`] lane by lane: the scalar lookup's own code.
pub(super) fn coords8_portable(to_local: &Mat3, width: usize, d: &[Vec3; 8]) -> Coords8 {
    let mut c = Coords8 {
        s: [0.0; 8],
        v: [0.0; 8],
        valid: 0,
    };
    for (k, &dk) in d.iter().enumerate() {
        let l = (*to_local * dk).unit_or_zero();
        if l != Vec3::ZERO {
            (c.s[k], c.v[k]) = map_coords(l, width);
            c.valid |= 1 << k;
        }
    }
    c
}

/// [`coords8`] in AVX2 registers.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn coords8_avx2(m: &Mat3, width: usize, d: &[Vec3; 8]) -> Coords8 {
    use crate::math::{ACOS_COEFFS, ATAN_COEFFS, PI, PI_LO};
    use core::arch::x86_64::*;
    let lanes = |f: fn(&Vec3) -> f32| {
        let a: [f32; 8] = core::array::from_fn(|k| f(&d[k]));
        // SAFETY: `a` holds eight f32, what an unaligned 256-bit load reads.
        unsafe { _mm256_loadu_ps(a.as_ptr()) }
    };
    let (dx, dy, dz) = (lanes(|v| v.x), lanes(|v| v.y), lanes(|v| v.z));
    let splat = |x: f32| _mm256_set1_ps(x);
    let (add, sub, mul, div) = (
        |a, b| _mm256_add_ps(a, b),
        |a, b| _mm256_sub_ps(a, b),
        |a, b| _mm256_mul_ps(a, b),
        |a, b| _mm256_div_ps(a, b),
    );
    // `b` where `mask` is set, else `a`.
    let select = |a, b, mask| _mm256_blendv_ps(a, b, mask);
    let sign = splat(-0.0);
    let abs = |a| _mm256_andnot_ps(sign, a);
    let horner = |x, c: [f32; 8]| {
        let mut p = splat(c[0]);
        for &k in &c[1..] {
            p = add(mul(p, x), splat(k));
        }
        p
    };
    // The rotation as glam's `Mat3 * Vec3`: (x_axis d.x + y_axis d.y) + z_axis d.z.
    let row =
        |x: f32, y: f32, z: f32| add(add(mul(splat(x), dx), mul(splat(y), dy)), mul(splat(z), dz));
    let lx = row(m.x_axis.x, m.y_axis.x, m.z_axis.x);
    let ly = row(m.x_axis.y, m.y_axis.y, m.z_axis.y);
    let lz = row(m.x_axis.z, m.y_axis.z, m.z_axis.z);
    // `unit_or_zero`: times 1 / sqrt((x x + y y) + z z) where that is finite and positive.
    let dot = add(add(mul(lx, lx), mul(ly, ly)), mul(lz, lz));
    let rcp = div(splat(1.0), _mm256_sqrt_ps(dot));
    let valid = _mm256_and_ps(
        _mm256_cmp_ps::<_CMP_GT_OQ>(rcp, _mm256_setzero_ps()),
        _mm256_cmp_ps::<_CMP_LT_OQ>(rcp, splat(f32::INFINITY)),
    );
    let (lx, ly, lz) = (mul(lx, rcp), mul(ly, rcp), mul(lz, rcp));
    // atan2(y = lx, x = -lz), as `math::arc::atan2` for finite arguments.
    let (y, x) = (lx, _mm256_xor_ps(lz, sign));
    let (ax, ay) = (abs(x), abs(y));
    let (lo, hi) = (_mm256_min_ps(ax, ay), _mm256_max_ps(ax, ay));
    let a = select(
        _mm256_setzero_ps(),
        div(lo, hi),
        _mm256_cmp_ps::<_CMP_GT_OQ>(hi, _mm256_setzero_ps()),
    );
    let mut r = mul(a, horner(mul(a, a), ATAN_COEFFS));
    let steep = add(sub(splat(0.5 * PI), r), splat(0.5 * PI_LO));
    r = select(r, steep, _mm256_cmp_ps::<_CMP_GT_OQ>(ay, ax));
    // The sign bit of `x` picks, as `is_sign_negative` does (negative zero included).
    r = select(r, add(sub(splat(PI), r), splat(PI_LO)), x);
    r = _mm256_or_ps(abs(r), _mm256_and_ps(y, sign));
    // s = atan2 / 2 pi * w - 1/2, wrapped into [0, w).
    let w = splat(width as f32);
    let mut s = sub(mul(mul(r, splat(INV_TWO_PI)), w), splat(0.5));
    let zero = _mm256_setzero_ps();
    s = select(s, add(s, w), _mm256_cmp_ps::<_CMP_LT_OQ>(s, zero));
    s = select(s, add(s, w), _mm256_cmp_ps::<_CMP_LT_OQ>(s, zero));
    s = select(s, sub(s, w), _mm256_cmp_ps::<_CMP_GE_OQ>(s, w));
    // v = acos(clamp(ly, -1, 1)) / pi, as `math::arc::acos`.
    let c = _mm256_max_ps(_mm256_min_ps(ly, splat(1.0)), splat(-1.0));
    let ac = abs(c);
    let q = mul(_mm256_sqrt_ps(sub(splat(1.0), ac)), horner(ac, ACOS_COEFFS));
    let q = select(
        q,
        add(sub(splat(PI), q), splat(PI_LO)),
        _mm256_cmp_ps::<_CMP_LT_OQ>(c, zero),
    );
    let v = mul(q, splat(INV_PI));
    let mut out = Coords8 {
        s: [0.0; 8],
        v: [0.0; 8],
        valid: _mm256_movemask_ps(valid) as u32,
    };
    // SAFETY: each array holds eight f32, what an unaligned 256-bit store writes.
    unsafe {
        _mm256_storeu_ps(out.s.as_mut_ptr(), s);
        _mm256_storeu_ps(out.v.as_mut_ptr(), v);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emitter::EnvMap;
    use alloc::vec::Vec;

    /// A rotation that mixes every axis (30 degrees about y, then 70 about x).
    fn tilted() -> Mat3 {
        Mat3::from_rotation_x(70f32.to_radians()) * Mat3::from_rotation_y(30f32.to_radians())
    }

    /// Directions that probe every branch: random ones of every length in a cube, the axes
    /// and the seams with signed zeros, the poles, and ones without a unit form.
    fn directions() -> Vec<Vec3> {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let mut d: Vec<Vec3> = (0..40_000)
            .map(|_| Vec3::new(next(), next(), next()))
            .collect();
        for x in [-1.0, -0.0, 0.0, 1.0] {
            for y in [-1.0, -0.0, 0.0, 1.0, 0.5] {
                for z in [-1.0, -0.0, 0.0, 1.0, -1e-30] {
                    d.push(Vec3::new(x, y, z));
                }
            }
        }
        d.extend([
            Vec3::splat(1e-30),
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(f32::INFINITY, 0.0, 1.0),
            Vec3::new(3e38, 3e38, 0.0),
        ]);
        while !d.len().is_multiple_of(8) {
            d.push(Vec3::Y);
        }
        d
    }

    fn bits(c: &Coords8) -> Vec<(u32, u32)> {
        (0..8)
            .filter(|k| c.valid >> k & 1 != 0)
            .map(|k| (c.s[k].to_bits(), c.v[k].to_bits()))
            .collect()
    }

    /// The AVX2 lanes give the portable (scalar) code's bits for every direction, with the
    /// same lanes valid. Control: a rotation one ten-thousandth of a degree away changes the
    /// bits of most lanes, so a comparison this strict notices a single rounding.
    #[test]
    fn avx2_coordinates_are_the_scalar_bits() {
        let Some(avx2) = Avx2::detect() else {
            return; // nothing to compare on this CPU: the portable version is the scalar code
        };
        let m = tilted();
        let near = Mat3::from_rotation_y(1e-4f32.to_radians()) * m;
        let (mut lanes, mut moved) = (0, 0);
        for chunk in directions().chunks_exact(8) {
            let d: [Vec3; 8] = chunk.try_into().expect("eight");
            for width in [512, 7, 1] {
                let fast = coords8(Some(avx2), &m, width, &d);
                let slow = coords8_portable(&m, width, &d);
                assert_eq!(fast.valid, slow.valid, "{d:?}");
                assert_eq!(bits(&fast), bits(&slow), "width {width}: {d:?}");
                let other = coords8_portable(&near, width, &d);
                lanes += bits(&slow).len();
                moved += bits(&slow)
                    .iter()
                    .zip(bits(&other))
                    .filter(|(a, b)| **a != *b)
                    .count();
            }
        }
        assert!(
            moved * 2 > lanes,
            "the control moved {moved} of {lanes} lanes"
        );
    }

    /// `eval8` is `eval` lane by lane, bit for bit, with and without AVX2, on a map with
    /// structure in every pixel.
    #[test]
    fn eval8_is_eval() {
        let (w, h) = (37, 19);
        let pixels: Vec<[f32; 3]> = (0..w * h)
            .map(|i| {
                [
                    (i % 7) as f32 * 0.3,
                    (i % 11) as f32 * 0.1,
                    (i / w) as f32 * 0.05,
                ]
            })
            .collect();
        let env = EnvMap::new(pixels, w, h, 1.5, tilted()).expect("a map");
        for chunk in directions().chunks_exact(8) {
            let d: [Vec3; 8] = chunk.try_into().expect("eight");
            let each: [Color; 8] = d.map(|dk| env.eval(dk));
            for avx2 in [None, Avx2::detect()] {
                let all = env.eval8(avx2, &d);
                for k in 0..8 {
                    assert_eq!(
                        all[k].to_array().map(f32::to_bits),
                        each[k].to_array().map(f32::to_bits),
                        "{:?} ({avx2:?})",
                        d[k]
                    );
                }
            }
        }
    }
}

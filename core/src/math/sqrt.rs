//! Square roots, and the vector lengths and normalisations built on them.
//!
//! `libm::sqrtf` (which glam's `length`, `normalize` and kin call in this workspace, since glam
//! runs on its `libm` backend) is inline assembly holding the legacy-SSE `sqrtss`. In a build for
//! an AVX CPU every other float instruction is VEX-encoded, and the compiler does not clear the
//! upper vector halves before an `asm!` block. On Intel cores a legacy-SSE instruction with dirty
//! upper halves pays a merge with the full register, which stalled Tessera's path loop: the
//! Cornell box at 128x128, 64 spp, 1 thread took 2.17 s with it and 1.30 s with the intrinsic
//! below (Xeon, Emerald Rapids; AMD Zen 4 showed no such penalty).
//!
//! [`sqrt`] calls the SSE intrinsic instead, which the compiler encodes as `vsqrtss` wherever AVX
//! is on. IEEE 754 square root is correctly rounded, so the bits are those of `libm::sqrtf` on
//! every target; [`sqrt_f64`] does the same for `f64`. [`Norm`] gives `Vec2`, `Vec3`, `DVec2`
//! and `DVec3` their lengths and normalisations with glam's exact arithmetic (the same products
//! and sums in the same order) on top of these. Clippy (`clippy.toml`) refuses glam's own
//! versions and libm's square roots in the workspace.
//!
//! libm's `acos` takes libm's square root inside; [`acos_f64`] clears the vector registers'
//! upper halves (`vzeroupper`) before calling it in builds for AVX CPUs, so that square root
//! finds nothing to merge. (The `f32` arc cosine is a polynomial of its own, in `arc.rs`.)
//!
//! [`sqrt4`] takes four square roots in one instruction, for code that holds four values in a
//! vector's lanes.
//!
//! The `unsafe` blocks are the intrinsic calls: `sqrtss`, `sqrtps` and `sqrtsd` are part of SSE and SSE2,
//! which every x86_64 CPU has, `vzeroupper` is compiled only for AVX CPUs, and none touches
//! memory.
#![allow(unsafe_code)]

use glam::{DVec2, DVec3, Vec2, Vec3, Vec4};

/// Correctly rounded `sqrt(x)` (NaN for negative `x`), as one `sqrtss`/`vsqrtss` on x86_64.
#[inline(always)]
#[allow(clippy::disallowed_methods)] // off x86_64, libm's is the hardware instruction
pub fn sqrt(x: f32) -> f32 {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_cvtss_f32, _mm_set_ss, _mm_sqrt_ss};
        // SAFETY: SSE is part of the x86_64 baseline; the intrinsics only move and compute
        // values in registers.
        unsafe { _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        libm::sqrtf(x)
    }
}

/// [`sqrt`] for `f64`: one `sqrtsd`/`vsqrtsd` on x86_64, `libm::sqrt` elsewhere.
#[inline(always)]
#[allow(clippy::disallowed_methods)] // off x86_64, libm's is the hardware instruction
pub fn sqrt_f64(x: f64) -> f64 {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_cvtsd_f64, _mm_set_sd, _mm_sqrt_sd};
        // SAFETY: SSE2 is part of the x86_64 baseline; the intrinsics only move and compute
        // values in registers.
        unsafe {
            let v = _mm_set_sd(x);
            _mm_cvtsd_f64(_mm_sqrt_sd(v, v))
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        libm::sqrt(x)
    }
}

/// [`sqrt`] of each of four lanes: one `sqrtps`/`vsqrtps` on x86_64, four [`sqrt`]s elsewhere.
/// Correctly rounded per lane, so each lane's bits are [`sqrt`]'s.
#[inline(always)]
pub fn sqrt4(v: Vec4) -> Vec4 {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{__m128, _mm_sqrt_ps};
        let m: __m128 = v.into();
        // SAFETY: SSE is part of the x86_64 baseline; the intrinsic only computes in registers.
        Vec4::from(unsafe { _mm_sqrt_ps(m) })
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        Vec4::new(sqrt(v.x), sqrt(v.y), sqrt(v.z), sqrt(v.w))
    }
}

/// `libm::acos`, which takes libm's legacy-SSE square root inside for `|x| > 1/2`, with the
/// vector registers' upper halves cleared first (`vzeroupper`) in builds for AVX CPUs, so that
/// square root pays no transition penalty. Same bits as `libm::acos`. (The `f32` version is
/// `acos` in `arc.rs`, a polynomial.)
#[inline]
#[allow(clippy::disallowed_methods)] // the wrapper the lint points to
pub fn acos_f64(x: f64) -> f64 {
    clear_upper_halves();
    libm::acos(x)
}

/// `vzeroupper` when compiled for AVX (nothing otherwise: without AVX no upper half is dirty).
#[inline(always)]
fn clear_upper_halves() {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    // SAFETY: this code is compiled only for CPUs with AVX; `vzeroupper` only zeroes the upper
    // halves of the vector registers, which the compiler treats as clobbered by it.
    unsafe {
        core::arch::x86_64::_mm256_zeroupper()
    }
}

/// Lengths and normalisations through [`sqrt`] (or [`sqrt_f64`]), with the arithmetic of
/// glam's methods of the same meaning (`length`, `normalize`, `normalize_or`, `try_normalize`,
/// `normalize_or_zero`), so swapping one for the other keeps every bit.
pub trait Norm: Sized + Copy {
    /// The component type.
    type Scalar;
    /// Euclidean length (glam's `length`).
    fn norm(self) -> Self::Scalar;
    /// `self` scaled by `1 / length` (glam's `normalize`): non-finite for a zero vector.
    fn unit(self) -> Self;
    /// The unit vector, or `fallback` when `1 / length` is not finite and positive (glam's
    /// `normalize_or`).
    fn unit_or(self, fallback: Self) -> Self;
    /// The unit vector, or `None` when it does not exist (glam's `try_normalize`).
    fn try_unit(self) -> Option<Self>;
    /// The unit vector, or zero when it does not exist (glam's `normalize_or_zero`).
    fn unit_or_zero(self) -> Self;
}

macro_rules! impl_norm {
    ($t:ty, $s:ty, $sqrt:ident) => {
        impl Norm for $t {
            type Scalar = $s;
            #[inline(always)]
            fn norm(self) -> $s {
                $sqrt(self.dot(self))
            }
            #[inline(always)]
            fn unit(self) -> Self {
                self * (1.0 / self.norm())
            }
            #[inline(always)]
            fn unit_or(self, fallback: Self) -> Self {
                self.try_unit().unwrap_or(fallback)
            }
            #[inline(always)]
            fn try_unit(self) -> Option<Self> {
                let rcp = 1.0 / self.norm();
                (rcp.is_finite() && rcp > 0.0).then(|| self * rcp)
            }
            #[inline(always)]
            fn unit_or_zero(self) -> Self {
                self.unit_or(<$t>::ZERO)
            }
        }
    };
}

impl_norm!(Vec2, f32, sqrt);
impl_norm!(Vec3, f32, sqrt);
impl_norm!(DVec2, f64, sqrt_f64);
impl_norm!(DVec3, f64, sqrt_f64);

#[cfg(test)]
mod tests {
    use super::*;

    /// Every float class and a spread of bit patterns: the same bits as `libm::sqrtf` (and, for
    /// `sqrt_f64`, `libm::sqrt`).
    #[test]
    #[allow(clippy::disallowed_methods)] // the comparison is the point
    fn sqrt_matches_libm_bit_for_bit() {
        let specials = [0.0f32, -0.0, 1.0, -1.0, f32::MIN_POSITIVE, 1e-45, f32::MAX];
        let specials = specials
            .into_iter()
            .chain([f32::INFINITY, f32::NEG_INFINITY]);
        let spread = (0..1u32 << 20).map(|i| f32::from_bits(i.wrapping_mul(4099) ^ (i << 12)));
        for x in specials.chain(spread) {
            let (a, b) = (sqrt(x), libm::sqrtf(x));
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{x:e}: {a} {b}"
            );
        }
        assert!(sqrt(f32::NAN).is_nan());
        let spread = (0..1u64 << 20).map(|i| f64::from_bits(i.wrapping_mul(0x9e37_79b9_7f4a_7c15)));
        for x in spread.chain([
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::INFINITY,
        ]) {
            let (a, b) = (sqrt_f64(x), libm::sqrt(x));
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{x:e}: {a} {b}"
            );
        }
    }

    /// The trait's vectors have glam's bits, including the zero, tiny and huge cases where
    /// normalisation fails or overflows.
    #[test]
    #[allow(clippy::disallowed_methods)] // the comparison is the point
    fn norm_matches_glam_bit_for_bit() {
        let same3 =
            |a: Vec3, b: Vec3| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits);
        let mut vs = [Vec3::ZERO, Vec3::X, Vec3::splat(1e-30), Vec3::splat(3e38)].to_vec();
        let mut s = 0x9e37_79b9u32;
        for _ in 0..10_000 {
            let mut c = [0.0; 3];
            for v in &mut c {
                s = s.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
                *v = (s >> 8) as f32 / (1u32 << 23) as f32 - 1.0;
            }
            vs.push(Vec3::from(c));
        }
        for v in vs {
            assert_eq!(v.norm().to_bits(), v.length().to_bits(), "{v}");
            if v.length() > 0.0 {
                assert!(same3(v.unit(), v.normalize()), "{v}");
            }
            assert!(same3(v.unit_or_zero(), v.normalize_or_zero()), "{v}");
            assert!(same3(v.unit_or(Vec3::Y), v.normalize_or(Vec3::Y)), "{v}");
            assert_eq!(
                v.try_unit().map(|u| u.to_array()),
                v.try_normalize().map(|u| u.to_array())
            );
            let w = v.truncate();
            assert_eq!(w.norm().to_bits(), w.length().to_bits(), "{w}");
            assert_eq!(
                w.unit_or_zero().to_array(),
                w.normalize_or_zero().to_array()
            );
        }
    }
}

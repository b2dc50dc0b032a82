//! Eight f32 lanes in one AVX register, for `lean x8 zsobol avx2` (`in_step_avx2.rs`): the few
//! operations that stage needs, each one IEEE instruction per lane (no fused multiply-add, no
//! approximations), so a lane computes exactly what the scalar code computes. The module is the
//! bench's only `unsafe`: the intrinsics, which this file is compiled to use only when the build
//! enables AVX2 (`-C target-cpu=native` on an AVX2 machine; see the `cfg` where it is included).
#![allow(unsafe_code)]

use core::arch::x86_64::*;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// Eight f32 lanes.
#[derive(Clone, Copy)]
pub struct F8(__m256);

/// Eight lane masks (all bits set: true).
#[derive(Clone, Copy)]
pub struct M8(__m256);

// SAFETY (every block below): the build enables AVX and AVX2 (this module is compiled only
// then), so the intrinsics are valid instructions; loads and stores touch only the eight f32s of
// the `[f32; 8]` they are given.
impl F8 {
    #[inline(always)]
    pub fn splat(x: f32) -> F8 {
        F8(unsafe { _mm256_set1_ps(x) })
    }
    #[inline(always)]
    pub fn load(a: &[f32; 8]) -> F8 {
        F8(unsafe { _mm256_loadu_ps(a.as_ptr()) })
    }
    #[inline(always)]
    pub fn store(self, a: &mut [f32; 8]) {
        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) }
    }
    #[inline(always)]
    pub fn sqrt(self) -> F8 {
        F8(unsafe { _mm256_sqrt_ps(self.0) })
    }
    #[inline(always)]
    pub fn floor(self) -> F8 {
        F8(unsafe { _mm256_floor_ps(self.0) })
    }
    #[inline(always)]
    pub fn abs(self) -> F8 {
        F8(unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0) })
    }
    /// `maxps`: `other` when either is NaN (what `f32::max` gives for a NaN `self` and a
    /// number `other`, the only way the stages use it).
    #[inline(always)]
    pub fn max(self, other: F8) -> F8 {
        F8(unsafe { _mm256_max_ps(self.0, other.0) })
    }
    /// `minps`: `other` when either is NaN (as [`F8::max`]).
    #[inline(always)]
    pub fn min(self, other: F8) -> F8 {
        F8(unsafe { _mm256_min_ps(self.0, other.0) })
    }
    #[inline(always)]
    pub fn is_nan(self) -> M8 {
        M8(unsafe { _mm256_cmp_ps::<_CMP_UNORD_Q>(self.0, self.0) })
    }
    /// The bits of `self` as eight u32s, `xor`ed with those of `m`.
    #[inline(always)]
    fn xor_bits(self, m: F8) -> F8 {
        F8(unsafe { _mm256_xor_ps(self.0, m.0) })
    }
}

impl M8 {
    /// Lane `i` true when bit `i` of `bits` is set.
    #[inline(always)]
    pub fn from_bits(bits: u32) -> M8 {
        unsafe {
            let b = _mm256_set1_epi32(bits as i32);
            let lane = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            let set = _mm256_cmpeq_epi32(_mm256_and_si256(b, lane), lane);
            M8(_mm256_castsi256_ps(set))
        }
    }
    /// Bit `i` set when lane `i` is true.
    #[inline(always)]
    pub fn bits(self) -> u32 {
        unsafe { _mm256_movemask_ps(self.0) as u32 }
    }
    #[inline(always)]
    pub fn and(self, o: M8) -> M8 {
        M8(unsafe { _mm256_and_ps(self.0, o.0) })
    }
    #[inline(always)]
    pub fn or(self, o: M8) -> M8 {
        M8(unsafe { _mm256_or_ps(self.0, o.0) })
    }
    /// `a` where true, else `b`.
    #[inline(always)]
    pub fn select(self, a: F8, b: F8) -> F8 {
        F8(unsafe { _mm256_blendv_ps(b.0, a.0, self.0) })
    }
}

/// Ordered comparisons (false when either side is NaN, as scalar `<`, `>`, `>=`, `==`;
/// `ne_ordered` is `!=` with neither side NaN).
macro_rules! compare {
    ($($f:ident => $pred:ident),*) => {
        impl F8 {
            $(
                #[inline(always)]
                pub fn $f(self, o: F8) -> M8 {
                    M8(unsafe { _mm256_cmp_ps::<$pred>(self.0, o.0) })
                }
            )*
        }
    };
}
compare!(lt => _CMP_LT_OQ, gt => _CMP_GT_OQ, ge => _CMP_GE_OQ, eq => _CMP_EQ_OQ,
    ne_ordered => _CMP_NEQ_OQ);

macro_rules! binop {
    ($tr:ident, $f:ident, $intr:ident) => {
        impl $tr for F8 {
            type Output = F8;
            #[inline(always)]
            fn $f(self, o: F8) -> F8 {
                F8(unsafe { $intr(self.0, o.0) })
            }
        }
    };
}
binop!(Add, add, _mm256_add_ps);
binop!(Sub, sub, _mm256_sub_ps);
binop!(Mul, mul, _mm256_mul_ps);
binop!(Div, div, _mm256_div_ps);

impl Neg for F8 {
    type Output = F8;
    /// A flip of the sign bit, as scalar negation.
    #[inline(always)]
    fn neg(self) -> F8 {
        self.xor_bits(F8::splat(-0.0))
    }
}

/// `v` moved one representable float away from zero in the direction of `off`'s sign, lane by
/// lane: the renderer's `step_away` (`core/src/math/float.rs`), the same select steps on the
/// bits.
#[inline(always)]
pub fn step_away(v: F8, off: F8) -> F8 {
    unsafe {
        let sign_bit = _mm256_set1_epi32(i32::MIN);
        let sign = _mm256_and_si256(_mm256_castps_si256(off.0), sign_bit);
        let y = _mm256_xor_si256(_mm256_castps_si256(v.0), sign);
        // -0.0 steps from +0.0.
        let is_neg_zero = _mm256_cmpeq_epi32(y, sign_bit);
        let b = _mm256_andnot_si256(is_neg_zero, y);
        // `b as i32 >= 0`: b > -1.
        let non_neg = _mm256_cmpgt_epi32(b, _mm256_set1_epi32(-1));
        let one = _mm256_set1_epi32(1);
        let stepped =
            _mm256_blendv_epi8(_mm256_sub_epi32(b, one), _mm256_add_epi32(b, one), non_neg);
        let yf = F8(_mm256_castsi256_ps(y));
        let keep_y = yf.is_nan().or(yf.eq(F8::splat(f32::INFINITY)));
        let up = keep_y.select(yf, F8(_mm256_castsi256_ps(stepped)));
        let r = F8(_mm256_castsi256_ps(_mm256_xor_si256(
            _mm256_castps_si256(up.0),
            sign,
        )));
        off.ne_ordered(F8::splat(0.0)).select(r, v)
    }
}

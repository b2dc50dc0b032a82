//! Inverse trigonometric functions in `f32` for the per-sample hot paths: the azimuth and
//! polar angle of a direction (an environment map's lookup, a sphere's texture coordinates).
//!
//! `libm::atan2f` and `libm::acosf` reduce their argument by branches on its range, and a
//! sample's direction is as good as random, so those branches mispredict often: a pair of calls
//! took about 35 ns on the reference machine. Here each is one polynomial on the reduced
//! argument with the quadrant applied by selects, about 15 ns for the pair. The polynomials are
//! weighted least-squares fits iterated towards the minimax relative error (Lawson's
//! algorithm; `atan(a) / a` in `a^2` on `[0, 1]`, degree 7; `acos(x) / sqrt(1 - x)` in `x` on
//! `[0, 1]`, degree 7), whose relative error is 1e-7 and 1.5e-8 before `f32` rounding.
//! Accuracy: within 2^-21 absolute of the exact value (two units in the last place of the
//! largest results, `[2, pi]`; libm's are within one), measured in the tests below. Plain `f32`
//! arithmetic, no fused multiply-add: the same bits on every target.
use super::poly::horner;
use super::{sqrt, PI};

/// The part of pi that `PI` (rounded to `f32`) leaves out.
pub(crate) const PI_LO: f32 = (core::f64::consts::PI - PI as f64) as f32;

/// The fit's constant term for `acos`: 1.5707963, one `f32` step below pi / 2 (what the fit
/// chose; written by its bits, as a decimal it reads as an approximation of pi / 2).
const ACOS_C0: f32 = f32::from_bits(0x3FC9_0FDA);

/// `atan(a) / a` as a polynomial in `a^2`, highest degree first (for [`horner`]).
pub(crate) const ATAN_COEFFS: [f32; 8] = [
    -0.004_693_273,
    0.024_252_396,
    -0.059_486_39,
    0.099_142_93,
    -0.140_194_82,
    0.199_697_24,
    -0.333_319_9,
    0.999_999_9,
];

/// `acos(x) / sqrt(1 - x)` as a polynomial in `x`, highest degree first.
pub(crate) const ACOS_COEFFS: [f32; 8] = [
    -0.001_253_456_3,
    0.006_638_617,
    -0.017_045_101,
    0.030_862_752,
    -0.050_164_19,
    0.088_977_315,
    -0.214_598_7,
    ACOS_C0,
];

/// `atan(a)` for `a` in `[0, 1]`.
#[inline(always)]
fn atan_unit(a: f32) -> f32 {
    a * horner(a * a, ATAN_COEFFS)
}

/// The angle of the point `(x, y)` from the positive x axis, in `[-pi, pi]` (the sign of `y`,
/// zeros included, as `atan2`). `atan2(0, 0)` is `0`; a NaN argument gives NaN; infinite
/// arguments are not supported (the callers pass components of unit vectors).
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    if y.is_nan() || x.is_nan() {
        return x + y;
    }
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    let a = if hi > 0.0 { lo / hi } else { 0.0 };
    let mut r = atan_unit(a);
    r = if ay > ax {
        (0.5 * PI - r) + 0.5 * PI_LO
    } else {
        r
    };
    r = if x.is_sign_negative() {
        (PI - r) + PI_LO
    } else {
        r
    };
    r.copysign(y)
}

/// The angle of `(x, y)` from the positive x axis as a fraction of a turn, in `[0, 1)` (the
/// texture coordinate of a sphere's or disk's longitude).
#[inline]
pub fn atan2_turns(y: f32, x: f32) -> f32 {
    let u = atan2(y, x) * super::INV_TWO_PI + 1.0;
    // `u` is in [1/2, 3/2]; above 1 the subtraction is exact (what `u % 1.0` gives, without
    // its call).
    if u >= 1.0 {
        u - 1.0
    } else {
        u
    }
}

/// `acos(x)` for `x` in `[-1, 1]`, in `[0, pi]`; NaN outside.
#[inline]
pub fn acos(x: f32) -> f32 {
    let ax = x.abs();
    let p = horner(ax, ACOS_COEFFS);
    let r = sqrt(1.0 - ax) * p;
    if x < 0.0 {
        (PI - r) + PI_LO
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;

    /// 2^-21: the bound both functions are held to.
    const BOUND: f64 = 1.0 / 2_097_152.0;

    /// Points on the unit sphere (xorshift, uniform in `z` and azimuth) plus the axes and
    /// diagonals.
    fn directions() -> Vec<[f32; 3]> {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f64 / (1u64 << 24) as f64
        };
        let mut v = Vec::new();
        for _ in 0..400_000 {
            let z = 1.0 - 2.0 * next();
            let p = 2.0 * core::f64::consts::PI * next();
            let r = crate::math::sqrt_f64(1.0 - z * z);
            v.push([
                (r * libm::cos(p)) as f32,
                z as f32,
                (r * libm::sin(p)) as f32,
            ]);
        }
        for a in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
            for b in [-1.0f32, -0.5, -0.0, 0.0, 0.5, 1.0] {
                v.push([a, b, a * b]);
            }
        }
        v
    }

    /// Largest absolute error of `f` against the `f64` reference over `directions()`.
    fn worst_atan2(f: impl Fn(f32, f32) -> f32) -> f64 {
        directions()
            .iter()
            .map(|d| {
                (f64::from(f(d[0], -d[2])) - libm::atan2(f64::from(d[0]), -f64::from(d[2]))).abs()
            })
            .fold(0.0, f64::max)
    }

    fn worst_acos(f: impl Fn(f32) -> f32) -> f64 {
        let mut xs: Vec<f32> = directions().iter().map(|d| d[1]).collect();
        xs.extend((0..=4096).map(|i| i as f32 / 2048.0 - 1.0));
        xs.extend([1.0 - f32::EPSILON, -1.0 + f32::EPSILON / 2.0, 1e-30, -1e-30]);
        xs.iter()
            .map(|&x| (f64::from(f(x)) - crate::math::acos_f64(f64::from(x))).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn atan2_within_bound() {
        let worst = worst_atan2(atan2);
        assert!(worst <= BOUND, "worst absolute error {worst:e}");
        // Control: an error of 2^-20 where the angle is near 3/4 pi is caught.
        let off = worst_atan2(|y, x| {
            let r = atan2(y, x);
            if (r - 2.4).abs() < 0.05 {
                r + 2.0 * BOUND as f32
            } else {
                r
            }
        });
        assert!(off > BOUND, "control not caught: {off:e}");
    }

    #[test]
    fn acos_within_bound() {
        let worst = worst_acos(acos);
        assert!(worst <= BOUND, "worst absolute error {worst:e}");
        // Control: an error of 2^-20 near x = 0 is caught.
        let off = worst_acos(|x| {
            if x.abs() < 0.01 {
                acos(x) + 2.0 * BOUND as f32
            } else {
                acos(x)
            }
        });
        assert!(off > BOUND, "control not caught: {off:e}");
    }

    #[test]
    fn exact_and_special_values() {
        assert_eq!(atan2(0.0, 0.0), 0.0);
        assert_eq!(atan2(0.0, 1.0), 0.0);
        assert!(atan2(-0.0, 1.0).is_sign_negative());
        assert_eq!(atan2(0.0, -1.0), PI);
        assert_eq!(atan2(-0.0, -1.0), -PI);
        assert_eq!(atan2(1.0, 0.0), 0.5 * PI);
        assert_eq!(atan2(-1.0, 0.0), -0.5 * PI);
        assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
        assert_eq!(acos(1.0), 0.0);
        assert_eq!(acos(-1.0), PI);
        assert!((f64::from(acos(0.0)) - core::f64::consts::FRAC_PI_2).abs() < 1e-7);
        assert!(acos(1.5).is_nan() && acos(-1.5).is_nan() && acos(f32::NAN).is_nan());
    }
}

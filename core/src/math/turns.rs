//! Sine and cosine of an angle given in turns (`2 pi u`), the form every direction sampler
//! uses for its azimuth.
//!
//! `libm::sincosf(2 pi u)` reduces the angle by branches on its range, and the azimuth of a
//! sample is as good as random, so those branches mispredict about half the time. Here the
//! nearest quarter turn is removed first, exactly (`u - k / 4` is exact by Sterbenz's lemma for
//! `|u| < 2^20`), which leaves at most an eighth of a turn, where one polynomial each gives the
//! sine and the cosine (fits iterated towards the minimax error, Lawson's algorithm:
//! `sin(2 pi f) / f` and `cos(2 pi f)` in `f^2` on `|f| <= 1/8`, degree 4, errors 5e-12 relative
//! and 5e-11 absolute before `f32` rounding). The quarter turn is then applied by swapping and
//! negating, which is exact. The result is at least as accurate as `sincosf(2 pi u)`, whose
//! argument is rounded once at full magnitude (tests below). Plain `f32` arithmetic: the same
//! bits on every target.
use super::poly::horner;
use super::PI;

/// `(sin(2 pi u), cos(2 pi u))`.
#[inline]
pub fn sincos_turns(u: f32) -> (f32, f32) {
    if !(u.abs() < 1_048_576.0) {
        return libm::sincosf(2.0 * PI * u);
    }
    let k = libm::roundf(4.0 * u);
    let f = u - 0.25 * k;
    let (s, c) = sincos_eighth(f);
    let q = k as i32;
    // Quadrant q: sin = s, c, -s, -c and cos = c, -s, -c, s.
    let (a, b) = if q & 1 == 0 { (s, c) } else { (c, s) };
    let sin_sign = if q & 2 == 0 { 1.0 } else { -1.0 };
    let cos_sign = if (q + 1) & 2 == 0 { 1.0 } else { -1.0 };
    (a * sin_sign, b * cos_sign)
}

/// `(sin(2 pi f), cos(2 pi f))` for `|f| <= 1/8`.
#[inline(always)]
fn sincos_eighth(f: f32) -> (f32, f32) {
    let t = f * f;
    let s = horner(t, [41.469_89, -76.697_78, 81.605_2, -41.341_7, TWO_PI]);
    let c = horner(t, [59.220_406, -85.442_856, 64.939_316, -19.739_208, 1.0]);
    (f * s, c)
}

/// 2 pi in `f32`.
const TWO_PI: f32 = 2.0 * PI;

#[cfg(test)]
mod tests {
    use super::*;

    /// Against f64 sine and cosine of the exact angle: within 1e-7 absolute (measured 8.6e-8,
    /// 1.5 f32 ulp near 1), and not worse than `sincosf(2 pi u)` on `[0, 1)` (which
    /// measured 4.1e-7 there, from rounding `2 pi u`).
    #[test]
    fn matches_f64_reference() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut worst = 0.0f64;
        let mut worst_libm = 0.0f64;
        let mut values: alloc::vec::Vec<f32> = (0..=64).map(|i| i as f32 / 64.0).collect();
        values.extend([-0.3, -1.75, 1e-9, 0.999_999_94, 3.125, -7.8, 1e5 + 0.37]);
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            values.push((x >> 40) as f32 / (1u64 << 24) as f32);
        }
        for &u in &values {
            let (s, c) = sincos_turns(u);
            let a = 2.0 * core::f64::consts::PI * f64::from(u);
            let (es, ec) = (libm::sin(a), libm::cos(a));
            let e = (f64::from(s) - es).abs().max((f64::from(c) - ec).abs());
            worst = worst.max(e);

            if (0.0..1.0).contains(&u) {
                let (ls, lc) = libm::sincosf(2.0 * PI * u);
                let el = (f64::from(ls) - es).abs().max((f64::from(lc) - ec).abs());
                worst_libm = worst_libm.max(el);
            }
        }
        assert!(worst < 1e-7, "worst absolute error {worst:e}");
        assert!(worst <= worst_libm, "{worst:e} vs libm {worst_libm:e}");
        // Control: a quadrant rule off by one turn of a quarter fails the bound.
        let (s, _) = sincos_turns(0.25);
        assert!((s - 1.0).abs() < 1e-7);
        let (s, c) = sincos_turns(0.5);
        assert!((s.abs() < 1e-7) && (c + 1.0).abs() < 1e-7);
        let (s, c) = sincos_turns(0.75);
        assert!((s + 1.0).abs() < 1e-7 && c.abs() < 1e-7);
    }

    #[test]
    fn huge_and_non_finite_fall_back() {
        assert_eq!(sincos_turns(3e7), libm::sincosf(2.0 * PI * 3e7));
        assert!(sincos_turns(f32::NAN).0.is_nan());
        assert!(sincos_turns(f32::INFINITY).1.is_nan());
    }
}

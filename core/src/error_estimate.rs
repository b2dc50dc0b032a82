//! How far a render is from converged, estimated from its own samples: the relative mean squared
//! error that `tessera bench` measures against a reference, without the reference.
//!
//! Method: two successive states of the accumulators, `before` (after `n_a` samples of a pixel)
//! and `after` (`n = n_a + n_b`). The mean of the first `n_a` samples, `A`, and the mean of the
//! `n_b` samples taken since, `B`, are two estimates of the pixel. If each sample contributed
//! variance `s^2`, `(B - A)^2` would have expectation `s^2 (1/n_a + 1/n_b)` and the pixel's mean
//! the variance `s^2 / n`, so the pixel's squared error is estimated by
//! `(B - A)^2 n_a n_b / n^2` (a quarter of `(B - A)^2` for equal halves). Each channel is divided by
//! `mean^2 + floor` as in the bench's relMSE, the channels and then the pixels are averaged.
//!
//! Why halves and not the sample variance: with a stratified sampler (`zsobol`) the error of a
//! pixel falls faster than `s^2 / n`, because its samples are not independent. The sample
//! variance ignores that and overstates the error, by 2 to 5 times at 16-128 spp on the Cornell
//! box and the Veach scene (`docs/design/adaptive-and-reuse.md`). Two halves that are each a well-spread set of samples (the
//! first and second halves of a power-of-two count) show the error the sampler really leaves. With
//! independent samples both estimates agree.
//!
//! One value per pixel is a very noisy estimate (three degrees of freedom), but the image mean
//! averages thousands of them. What no estimate from the samples can see is light the render has
//! not found yet (a rare bright path): at low sample counts the estimate can be low. Callers
//! therefore start checking only from [`MIN_CHECK_SPP`].
use crate::film::PixelAccum;

/// The fewest samples per pixel (mean) at which a stopping rule should trust the estimate.
pub const MIN_CHECK_SPP: u64 = 16;

/// Estimated relative MSE of the image `after` holds, from the state `before` it (see the module
/// notes); `floor` is added to `mean^2` (0.01 for the bench's measure).
///
/// A pixel that took no samples since `before` (possible in adaptive passes) or had none before
/// it contributes its sample variance over its count instead, `None` when it has fewer than two
/// samples.
///
/// # Panics
/// If the two slices differ in length.
pub fn halves_rel_mse(before: &[PixelAccum], after: &[PixelAccum], floor: f64) -> Option<f64> {
    assert_eq!(
        before.len(),
        after.len(),
        "halves_rel_mse: the two states differ in size"
    );
    if after.is_empty() {
        return None;
    }
    let mut total = 0.0f64;
    for (a, p) in before.iter().zip(after) {
        total += pixel_rel_mse(a, p, floor)?;
    }
    Some(total / after.len() as f64)
}

/// One pixel's term of [`halves_rel_mse`].
fn pixel_rel_mse(before: &PixelAccum, after: &PixelAccum, floor: f64) -> Option<f64> {
    let (na, n) = (before.count, after.count);
    let nb = n.saturating_sub(na);
    if na == 0 || nb == 0 {
        return Some(crate::adaptive::relative_variance(after, floor)? / n as f64);
    }
    let (na, nb, n) = (na as f64, nb as f64, n as f64);
    let mut e = 0.0;
    for c in 0..3 {
        let a = before.sum[c] / na;
        let b = (after.sum[c] - before.sum[c]) / nb;
        let mean = after.sum[c] / n;
        e += (b - a) * (b - a) * (na * nb / (n * n)) / (mean * mean + floor);
    }
    Some(e / 3.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adaptive::tests::pixel;
    use crate::Color;
    use alloc::vec::Vec;

    /// Known halves: first half mean 1, second half mean 2 (2 + 2 samples, mean 1.5): error
    /// estimate (2 - 1)^2 * 2 * 2 / 16 / (1.5^2 + 0.01).
    #[test]
    fn known_halves() {
        let before = pixel(&[0.5, 1.5]);
        let after = pixel(&[0.5, 1.5, 2.0, 2.0]);
        let e = halves_rel_mse(&[before], &[after], 0.01).unwrap();
        let want = 0.25 / (2.25 + 0.01);
        assert!((e - want).abs() < 1e-12, "{e} vs {want}");
        // Unequal halves: 1 sample then 3.
        let before = pixel(&[1.0]);
        let after = pixel(&[1.0, 3.0, 3.0, 3.0]);
        let e = halves_rel_mse(&[before], &[after], 0.0).unwrap();
        let want = 4.0 * 3.0 / 16.0 / (2.5 * 2.5);
        assert!((e - want).abs() < 1e-12, "{e} vs {want}");
    }

    /// Equal halves give zero even when the samples vary (the control: the sample variance of
    /// the same pixel is not zero), and a pixel without new samples falls back on the variance.
    #[test]
    fn halves_see_what_the_variance_does_not() {
        let before = pixel(&[0.0, 2.0]);
        let after = pixel(&[0.0, 2.0, 2.0, 0.0]);
        assert_eq!(halves_rel_mse(&[before], &[after], 0.01), Some(0.0));
        let v = crate::adaptive::relative_variance(&after, 0.01).unwrap();
        assert!(v > 1.0, "{v}");
        let e = halves_rel_mse(&[after], &[after], 0.01).unwrap();
        assert!((e - v / 4.0).abs() < 1e-12, "{e} vs {v}");
        assert_eq!(halves_rel_mse(&[pixel(&[])], &[pixel(&[1.0])], 0.01), None);
        assert_eq!(halves_rel_mse(&[], &[], 0.01), None);
    }

    /// With independent samples the squared-error estimate is unbiased: averaged over many
    /// pixels of uniform noise it matches the true squared error of the means. A huge `floor`
    /// makes every denominator the same, so this checks the numerator alone. Tolerance 4%: the
    /// estimate and the truth each have about 0.7% standard deviation over 40,000 pixels, and a
    /// wrong weight of the halves (such as a missing `n_a n_b / n^2`) is off by a factor of 4.
    #[test]
    fn unbiased_for_independent_samples() {
        let mut state = 0x1234_5678_9abc_def0u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 40) as f32) / (1u64 << 24) as f32
        };
        let (pixels, n, floor) = (40_000, 16, 1e6);
        let (mut before, mut after) = (Vec::new(), Vec::new());
        let mut truth = 0.0f64;
        for _ in 0..pixels {
            // Each channel's samples uniform on [0, 2): mean 1, variance 1/3.
            let s: Vec<Color> = (0..n)
                .map(|_| Color::new(2.0 * next(), 2.0 * next(), 2.0 * next()))
                .collect();
            let mut p = PixelAccum::default();
            for (i, &c) in s.iter().enumerate() {
                if i == n / 2 {
                    before.push(p);
                }
                p.add(c);
            }
            for c in 0..3 {
                let m = p.sum[c] / n as f64;
                truth += (m - 1.0) * (m - 1.0) / 3.0;
            }
            after.push(p);
        }
        truth /= pixels as f64;
        let expected = 1.0 / 3.0 / n as f64;
        assert!(
            (truth / expected - 1.0).abs() < 0.04,
            "{truth} vs {expected}"
        );
        let e = halves_rel_mse(&before, &after, floor).unwrap() * floor;
        assert!(
            (e / truth - 1.0).abs() < 0.04,
            "estimate {e}, truth {truth}"
        );
    }
}

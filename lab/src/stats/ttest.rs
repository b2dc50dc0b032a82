//! Student's t-tests for means of Monte Carlo estimators.
//!
//! # Method
//!
//! An unbiased estimator's sample mean over `n` independent samples is, for large `n`,
//! normally distributed around the true value with standard error `s / sqrt(n)`, where `s²` is
//! the unbiased sample variance. The statistic
//!
//! ```text
//! t = (mean - reference) / (s / sqrt(n))
//! ```
//!
//! then follows Student's t distribution with `n - 1` degrees of freedom, and the two-sided
//! p-value is `P(|T| >= |t|) = 2 · sf(|t|)` (computed with `statrs`). A biased estimator gives
//! `|t|` growing like `sqrt(n)`, so enough samples reject any fixed bias.
//!
//! - [`t_test_mean`] tests a [`Moments`] accumulator against a reference value.
//! - [`t_test_from_sums`] does the same from `n`, `Σx`, `Σx²` as a renderer accumulates them
//!   per pixel.
//! - [`welch_test`] compares two independent means with unequal variances (Welch's t-test,
//!   Welch–Satterthwaite degrees of freedom), e.g. the same region of two renders.
//!
//! Zero variance is a degenerate case: the mean is then exact, so the test passes (`p = 1`)
//! if it equals the reference and fails (`p = 0`) otherwise. "Equal" allows for the round-off
//! of computing a mean (a few ulps; `n` ulps for [`t_test_from_sums`], whose sums were
//! accumulated naively), and so does "zero variance" for [`t_test_from_sums`], where the sum
//! of squared deviations is only known up to the round-off of `Σx²`.
//!
//! At least two samples are needed for a variance; the functions panic otherwise (a test with
//! one sample is a bug in the test).

use std::fmt;

use statrs::distribution::{ContinuousCDF, StudentsT};

/// Running mean and variance of a stream of `f64` values.
///
/// Numerically careful without Welford's update: values are accumulated *shifted* by the
/// first value `K` (`Σ(x - K)`, `Σ(x - K)²`, both with Neumaier-compensated summation), so the
/// variance `(Σd² - (Σd)²/n) / (n - 1)` does not suffer the catastrophic cancellation of the
/// textbook `Σx² - (Σx)²/n` when the mean is large compared to the spread.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Moments {
    n: u64,
    shift: f64,
    sum: f64,
    sum_comp: f64,
    sum_sq: f64,
    sum_sq_comp: f64,
}

/// Neumaier (improved Kahan) compensated addition of `x` to `sum` with compensation `comp`.
fn neumaier_add(sum: &mut f64, comp: &mut f64, x: f64) {
    let t = *sum + x;
    if sum.abs() >= x.abs() {
        *comp += (*sum - t) + x;
    } else {
        *comp += (x - t) + *sum;
    }
    *sum = t;
}

impl Moments {
    /// An empty accumulator.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one sample.
    pub fn push(&mut self, x: f64) {
        if self.n == 0 {
            self.shift = x;
        }
        let d = x - self.shift;
        neumaier_add(&mut self.sum, &mut self.sum_comp, d);
        neumaier_add(&mut self.sum_sq, &mut self.sum_sq_comp, d * d);
        self.n += 1;
    }

    /// Number of samples pushed.
    pub fn count(&self) -> u64 {
        self.n
    }

    /// Sample mean (NaN if empty).
    pub fn mean(&self) -> f64 {
        if self.n == 0 {
            return f64::NAN;
        }
        self.shift + (self.sum + self.sum_comp) / self.n as f64
    }

    /// Unbiased sample variance `Σ(x - mean)² / (n - 1)` (NaN with fewer than 2 samples).
    pub fn variance(&self) -> f64 {
        if self.n < 2 {
            return f64::NAN;
        }
        let n = self.n as f64;
        let s = self.sum + self.sum_comp;
        let s2 = self.sum_sq + self.sum_sq_comp;
        ((s2 - s * s / n) / (n - 1.0)).max(0.0)
    }

    /// Standard error of the mean, `sqrt(variance / n)`.
    pub(crate) fn std_error(&self) -> f64 {
        (self.variance() / self.n as f64).sqrt()
    }

    /// `(n, mean, variance)`, the argument format of [`welch_test`].
    pub fn summary(&self) -> (f64, f64, f64) {
        (self.n as f64, self.mean(), self.variance())
    }
}

/// Outcome of a t-test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TTest {
    /// The t statistic (`±inf` when the variance is 0 and the means differ, 0 when they agree).
    pub t: f64,
    /// Degrees of freedom (`n - 1`, or Welch–Satterthwaite's non-integer value).
    pub dof: f64,
    /// Two-sided p-value `P(|T| >= |t|)`. Reject when `p_value < alpha`.
    pub p_value: f64,
}

impl TTest {
    /// `true` if the null hypothesis (equal means) survives at level `alpha`
    /// (`p_value >= alpha`; a NaN p-value never passes).
    pub fn passes(&self, alpha: f64) -> bool {
        self.p_value >= alpha
    }
}

impl fmt::Display for TTest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "t = {:.4}, dof = {:.2}, p = {:.4e}",
            self.t, self.dof, self.p_value
        )
    }
}

/// Two-sided p-value of `t` under Student's t with `dof` degrees of freedom.
fn two_sided_p(t: f64, dof: f64) -> f64 {
    if t.is_nan() || dof.is_nan() {
        return f64::NAN;
    }
    let dist = StudentsT::new(0.0, 1.0, dof).expect("t-test: degrees of freedom must be > 0");
    (2.0 * dist.sf(t.abs())).min(1.0)
}

/// The test of `diff = mean - reference` with squared standard error `se2`, handling zero
/// variance (see module docs); `equal_tol` is the tolerance for "equal means" in that case.
fn t_test(diff: f64, se2: f64, dof: f64, equal_tol: f64) -> TTest {
    if se2 == 0.0 {
        return if diff.abs() <= equal_tol {
            TTest {
                t: 0.0,
                dof,
                p_value: 1.0,
            }
        } else {
            TTest {
                t: diff.signum() * f64::INFINITY,
                dof,
                p_value: 0.0,
            }
        };
    }
    let t = diff / se2.sqrt();
    TTest {
        t,
        dof,
        p_value: two_sided_p(t, dof),
    }
}

/// Round-off tolerance for comparing two means `a` and `b` computed with relative error `ulps`.
fn equal_tolerance(a: f64, b: f64, ulps: f64) -> f64 {
    ulps * f64::EPSILON * a.abs().max(b.abs())
}

/// One-sample, two-sided Student t-test of `H0: E[x] = reference` on accumulated samples.
///
/// # Panics
/// With fewer than 2 samples.
pub fn t_test_mean(m: &Moments, reference: f64) -> TTest {
    assert!(
        m.count() >= 2,
        "t-test needs at least 2 samples, got {}",
        m.count()
    );
    let n = m.count() as f64;
    let mean = m.mean();
    t_test(
        mean - reference,
        m.variance() / n,
        n - 1.0,
        equal_tolerance(mean, reference, 4.0),
    )
}

/// [`t_test_mean`] for samples computed in single precision: the renderer's answer carries a few
/// f32 ulps of rounding that no number of samples removes, so `(4 f32 ulps of the reference)^2`
/// joins the squared standard error. Near-zero-variance estimators (a point light, BSDF sampling
/// in a furnace) are then held to f32 precision rather than beyond it.
///
/// # Panics
/// With fewer than 2 samples.
pub fn t_test_mean_f32(m: &Moments, reference: f64) -> TTest {
    assert!(
        m.count() >= 2,
        "t-test needs at least 2 samples, got {}",
        m.count()
    );
    let n = m.count() as f64;
    let floor = 4.0 * f32::EPSILON as f64 * reference.abs();
    let se2 = m.variance() / n + floor * floor;
    t_test(
        m.mean() - reference,
        se2,
        n - 1.0,
        equal_tolerance(m.mean(), reference, 4.0),
    )
}

/// One-sample, two-sided Student t-test of `H0: E[x] = reference` from the count `n`, `sum`
/// `= Σx` and `sum_sq = Σx²` (as accumulated per pixel by the renderer, in f64).
///
/// The variance `(Σx² - (Σx)²/n) / (n - 1)` loses precision when the mean is large compared to
/// the spread; a result within the round-off of `Σx²` (`n` ulps, the worst case of naive
/// summation) counts as zero variance, and the means are then compared within `n` ulps.
///
/// # Panics
/// If `n < 2`.
pub fn t_test_from_sums(n: f64, sum: f64, sum_sq: f64, reference: f64) -> TTest {
    assert!(n >= 2.0, "t-test needs at least 2 samples, got {n}");
    let mean = sum / n;
    let ulps = n.max(4.0);
    let ss = sum_sq - sum * mean; // Σ(x - mean)²
    let var = if ss <= ulps * f64::EPSILON * sum_sq.abs() {
        0.0
    } else {
        ss / (n - 1.0)
    };
    t_test(
        mean - reference,
        var / n,
        n - 1.0,
        equal_tolerance(mean, reference, ulps),
    )
}

/// Welch's two-sample, two-sided t-test of `H0: E[a] = E[b]`; each argument is
/// `(n, mean, unbiased variance)` (see [`Moments::summary`]). Degrees of freedom by
/// Welch–Satterthwaite: `(va/na + vb/nb)² / ((va/na)²/(na-1) + (vb/nb)²/(nb-1))`.
///
/// # Panics
/// If either `n < 2` or a variance is negative.
pub fn welch_test(a: (f64, f64, f64), b: (f64, f64, f64)) -> TTest {
    let ((na, ma, va), (nb, mb, vb)) = (a, b);
    assert!(
        na >= 2.0 && nb >= 2.0,
        "Welch's t-test needs at least 2 samples per group"
    );
    assert!(!(va < 0.0 || vb < 0.0), "Welch's t-test: negative variance");
    let (ea, eb) = (va / na, vb / nb);
    let se2 = ea + eb;
    let dof = if se2 == 0.0 {
        na + nb - 2.0
    } else {
        se2 * se2 / (ea * ea / (na - 1.0) + eb * eb / (nb - 1.0))
    };
    t_test(ma - mb, se2, dof, equal_tolerance(ma, mb, 4.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::rng::Pcg32;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    fn moments(xs: &[f64]) -> Moments {
        let mut m = Moments::new();
        xs.iter().for_each(|&x| m.push(x));
        m
    }

    #[test]
    fn textbook_values() {
        // [1, 2, 3] against 0: mean 2, s = 1, t = 2 sqrt(3), 2 dof, where the two-sided
        // p-value has the closed form 1 - t / sqrt(2 + t²).
        let r = t_test_mean(&moments(&[1.0, 2.0, 3.0]), 0.0);
        assert!(close(r.t, 2.0 * 3f64.sqrt(), 1e-14), "{r}");
        assert_eq!(r.dof, 2.0);
        assert!(close(r.p_value, 0.07417990022744858, 1e-10), "{r}");

        // [1..5] against 2: mean 3, var 2.5, se sqrt(0.5), t = sqrt(2), 4 dof, p = 0.2302.
        let m = moments(&[1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!((m.count(), m.mean(), m.variance()), (5, 3.0, 2.5));
        assert!(close(m.std_error(), 0.5f64.sqrt(), 1e-15));
        let r = t_test_mean(&m, 2.0);
        assert!(close(r.t, 2f64.sqrt(), 1e-14), "{r}");
        assert!(close(r.p_value, 0.2301996410805125, 1e-8), "{r}");

        // Table value: t = 2.228 is the two-sided 5% critical value for 10 dof.
        assert!(close(two_sided_p(2.228138851986274, 10.0), 0.05, 1e-9));
        assert!(close(two_sided_p(-2.228138851986274, 10.0), 0.05, 1e-9));
        assert_eq!(two_sided_p(0.0, 10.0), 1.0);
    }

    #[test]
    fn moments_are_numerically_careful() {
        // The classic: 1e9 + {4, 7, 13, 16} has variance 30; naive Σx² - (Σx)²/n is ruined.
        let m = moments(&[1e9 + 4.0, 1e9 + 7.0, 1e9 + 13.0, 1e9 + 16.0]);
        assert_eq!(m.mean(), 1e9 + 10.0);
        assert!(close(m.variance(), 30.0, 1e-12), "{}", m.variance());
        let m = moments(&[5.0]);
        assert!(m.variance().is_nan());
        assert!(Moments::new().mean().is_nan());
    }

    #[test]
    fn from_sums_matches_moments() {
        let xs = [0.3, 1.7, 0.2, 2.9, 1.1, 0.4, 0.8];
        let (s, s2) = xs
            .iter()
            .fold((0.0, 0.0), |(s, s2), &x| (s + x, s2 + x * x));
        let a = t_test_mean(&moments(&xs), 1.0);
        let b = t_test_from_sums(xs.len() as f64, s, s2, 1.0);
        assert!(
            close(a.t, b.t, 1e-12) && close(a.p_value, b.p_value, 1e-10),
            "{a} vs {b}"
        );
        assert_eq!(a.dof, b.dof);
    }

    #[test]
    fn normal_samples_pass_and_biased_reference_fails() {
        // 1e6 samples of N(0.5, 1): standard error 0.001, so 0.52 is 20 standard errors away.
        let mut rng = Pcg32::new(21);
        let mut m = Moments::new();
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..1_000_000 {
            let x = 0.5 + rng.next_normal();
            m.push(x);
            s += x;
            s2 += x * x;
        }
        assert!(close(m.variance(), 1.0, 0.01), "{}", m.variance());
        let good = t_test_mean(&m, 0.5);
        assert!(good.passes(0.01), "{good}");
        let bad = t_test_mean(&m, 0.52);
        assert!(bad.p_value < 1e-6, "{bad}");
        let good = t_test_from_sums(1e6, s, s2, 0.5);
        assert!(good.passes(0.01), "{good}");
        let bad = t_test_from_sums(1e6, s, s2, 0.52);
        assert!(bad.p_value < 1e-6, "{bad}");
    }

    #[test]
    fn welch() {
        // Computed by hand: se² = 4/10 + 9/20 = 0.85, t = -2 / sqrt(0.85),
        // dof = 0.85² / (0.4²/9 + 0.45²/19) = 25.408; p by numerical integration of the density.
        let r = welch_test((10.0, 20.0, 4.0), (20.0, 22.0, 9.0));
        assert!(close(r.t, -2.1693045781865616, 1e-14), "{r}");
        assert!(close(r.dof, 25.408226221079694, 1e-12), "{r}");
        assert!(close(r.p_value, 0.039610778035955474, 1e-7), "{r}");

        // Power: two renders' region means, equal vs 1% apart, 1e6 samples each.
        let mut rng = Pcg32::new(22);
        let (mut a, mut b, mut c) = (Moments::new(), Moments::new(), Moments::new());
        for _ in 0..1_000_000 {
            a.push(0.5 + rng.next_normal());
            b.push(0.5 + 2.0 * rng.next_normal());
            c.push(0.51 + 2.0 * rng.next_normal());
        }
        let same = welch_test(a.summary(), b.summary());
        assert!(same.passes(0.01), "{same}");
        let differ = welch_test(a.summary(), c.summary());
        assert!(differ.p_value < 1e-3, "{differ}");
    }

    #[test]
    fn zero_variance() {
        let m = moments(&[0.25; 10]);
        assert_eq!(t_test_mean(&m, 0.25).p_value, 1.0);
        let r = t_test_mean(&m, 0.2500001);
        assert_eq!(r.p_value, 0.0);
        assert_eq!(r.t, f64::NEG_INFINITY);
        // Naive sums of 1e6 copies of 0.1 carry round-off; still "zero variance, equal mean".
        let (mut s, mut s2) = (0.0f64, 0.0f64);
        for _ in 0..1_000_000 {
            s += 0.1;
            s2 += 0.1 * 0.1;
        }
        assert_eq!(t_test_from_sums(1e6, s, s2, 0.1).p_value, 1.0);
        assert_eq!(t_test_from_sums(1e6, s, s2, 0.1001).p_value, 0.0);
        assert_eq!(welch_test((5.0, 1.0, 0.0), (7.0, 1.0, 0.0)).p_value, 1.0);
        assert_eq!(welch_test((5.0, 1.0, 0.0), (7.0, 1.5, 0.0)).p_value, 0.0);
    }

    #[test]
    #[should_panic(expected = "at least 2 samples")]
    fn one_sample_is_a_bug() {
        t_test_mean(&moments(&[1.0]), 1.0);
    }
}

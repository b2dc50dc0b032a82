//! Pearson's chi-square goodness-of-fit test with pooling of sparse cells.
//!
//! # Method
//!
//! Samples are counted in `k` cells (`observed`), and the code under test predicts how many
//! should land in each (`expected`, i.e. the number of samples times the probability of the
//! cell). If the prediction is right, the statistic
//!
//! ```text
//! X^2 = sum_i (O_i - E_i)^2 / E_i
//! ```
//!
//! is approximately chi-square distributed with `k - 1` degrees of freedom (all parameters are
//! known; none is fitted, so no further degrees of freedom are removed). The p-value is the
//! survival function `P(chi2_{k-1} >= X^2)`, computed with `statrs`.
//!
//! The approximation needs every cell's expectation to be reasonably large (the usual rule is
//! 5). As in Nori's `ChiSquareTest`, cells are sorted by expected count, the ones below
//! `min_expected` are accumulated into one pooled cell, and if that pool is still below
//! `min_expected` it is merged into the next (smallest non-small) cell. `pooled_cells` reports
//! how many original cells went into the pooled cell.
//!
//! Cells with expected count exactly 0 are left out (they carry no information) — unless a
//! sample landed there: that is a sample the pdf calls impossible, and the test fails at once
//! with `p_value = 0` and a message. Negative or non-finite expectations (a broken pdf) fail the
//! same way.
//!
//! When several tests are run and the suite should fail with probability `alpha` overall if
//! everything is correct, each test uses the Šidák-corrected level [`sidak_alpha`].

use std::fmt;

use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Expected count below which a cell is pooled with others (the textbook rule of thumb, as in
/// Nori and Mitsuba).
pub const DEFAULT_MIN_EXPECTED: f64 = 5.0;

/// Largest accepted deviation of a sampler's pdf integral from 1 (when the sampler never
/// fails) in `SphereChi2` and `PlaneChi2`. Far above
/// the cubature error, and below what the chi-square test itself can see at 1e6 samples.
pub const PDF_INTEGRAL_TOLERANCE: f64 = 1e-3;

/// Outcome of a chi-square goodness-of-fit test.
#[derive(Clone, Debug, PartialEq)]
pub struct Chi2Result {
    /// Pearson's statistic `sum (O - E)^2 / E` over the cells after pooling (`+inf` when the
    /// test failed before it could be computed).
    pub statistic: f64,
    /// Degrees of freedom: number of cells after pooling minus one.
    pub dof: usize,
    /// Probability of a statistic at least this large if the null hypothesis (the expected
    /// counts are right) holds. Reject when `p_value < alpha`. Set to 0 for immediate failures
    /// (see `message`).
    pub p_value: f64,
    /// Number of original cells merged into the pooled cell (0 if no pooling happened).
    pub pooled_cells: usize,
    /// Numerical integral of the pdf over the whole domain, for the samplers' tests
    /// (`SphereChi2`, `PlaneChi2`); `None` from
    /// [`chi2_test`] itself.
    pub pdf_integral: Option<f64>,
    /// Why the test failed outright (`p_value` forced to 0), e.g. samples in a cell whose
    /// expected count is 0, or a pdf that does not integrate to 1. `None` otherwise.
    pub message: Option<String>,
}

impl Chi2Result {
    /// An immediate failure: `p_value = 0`, infinite statistic, with an explanation.
    pub(crate) fn failure(message: String) -> Self {
        Chi2Result {
            statistic: f64::INFINITY,
            dof: 0,
            p_value: 0.0,
            pooled_cells: 0,
            pdf_integral: None,
            message: Some(message),
        }
    }

    /// Forces the result to a failure (`p_value = 0`), appending `message` to any earlier one.
    pub(crate) fn fail_with(&mut self, message: String) {
        self.p_value = 0.0;
        self.message = Some(match self.message.take() {
            Some(old) => format!("{old}; {message}"),
            None => message,
        });
    }

    /// Records the pdf's integral over the domain and fails the test if it is inconsistent:
    /// it must be 1 when the sampler never failed (`failures == 0`), and at most 1 otherwise
    /// (then it is the probability that a sample succeeds).
    pub(crate) fn check_pdf_integral(&mut self, integral: f64, failures: usize) {
        self.pdf_integral = Some(integral);
        if failures == 0 && (integral - 1.0).abs() > PDF_INTEGRAL_TOLERANCE {
            self.fail_with(format!(
                "the pdf integrates to {integral:.6} over the domain, not 1, although the \
                 sampler never failed"
            ));
        } else if failures > 0 && integral > 1.0 + PDF_INTEGRAL_TOLERANCE {
            self.fail_with(format!(
                "the pdf integrates to {integral:.6} > 1 over the domain"
            ));
        }
    }

    /// `true` if the null hypothesis survives at significance level `alpha`
    /// (`p_value >= alpha`; a NaN p-value never passes).
    pub fn passes(&self, alpha: f64) -> bool {
        self.p_value >= alpha
    }
}

impl fmt::Display for Chi2Result {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "chi2 = {:.4}, dof = {}, p = {:.4e}, pooled cells = {}",
            self.statistic, self.dof, self.p_value, self.pooled_cells
        )?;
        if let Some(integral) = self.pdf_integral {
            write!(f, ", pdf integral = {integral:.6}")?;
        }
        if let Some(message) = &self.message {
            write!(f, ": {message}")?;
        }
        Ok(())
    }
}

/// Pearson's chi-square goodness-of-fit test of `observed` counts against `expected` counts,
/// pooling cells whose expected count is below `min_expected` (use [`DEFAULT_MIN_EXPECTED`]).
///
/// Cells with zero expectation and zero observation are ignored; a cell with zero expectation
/// but a positive observation, or an invalid (negative / non-finite) count, fails immediately
/// with `p_value = 0` and a `message`. Fewer than two cells after pooling also fails (the test
/// would have no power: add samples or bins).
///
/// # Panics
/// If the slices differ in length or `min_expected` is negative or not finite.
pub fn chi2_test(observed: &[f64], expected: &[f64], min_expected: f64) -> Chi2Result {
    assert_eq!(
        observed.len(),
        expected.len(),
        "chi2_test: observed and expected have different numbers of cells"
    );
    assert!(
        min_expected.is_finite() && min_expected >= 0.0,
        "chi2_test: min_expected must be finite and non-negative, got {min_expected}"
    );

    let mut cells: Vec<(f64, f64)> = Vec::with_capacity(observed.len());
    for (i, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if !(e.is_finite() && e >= 0.0) {
            return Chi2Result::failure(format!(
                "cell {i}: expected count {e} is negative or not finite (broken pdf?)"
            ));
        }
        if !(o.is_finite() && o >= 0.0) {
            return Chi2Result::failure(format!(
                "cell {i}: observed count {o} is negative or not finite"
            ));
        }
        if e == 0.0 {
            if o > 0.0 {
                return Chi2Result::failure(format!(
                    "cell {i}: {o} samples observed in a cell with expected count 0 \
                     (the sampler produces values the pdf calls impossible)"
                ));
            }
            continue;
        }
        cells.push((o, e));
    }
    cells.sort_by(|a, b| a.1.total_cmp(&b.1));

    // Sorted ascending, so the small cells form a prefix.
    let split = cells.partition_point(|&(_, e)| e < min_expected);
    let (small, big) = cells.split_at(split);
    let mut pool_o: f64 = small.iter().map(|c| c.0).sum();
    let mut pool_e: f64 = small.iter().map(|c| c.1).sum();
    let mut pooled_cells = small.len();
    let mut rest = big;
    if pooled_cells > 0 && pool_e < min_expected && !big.is_empty() {
        // Still too small: merge the pool into the smallest remaining cell.
        pool_o += big[0].0;
        pool_e += big[0].1;
        pooled_cells += 1;
        rest = &big[1..];
    }

    let mut statistic = 0.0;
    let mut n_cells = 0usize;
    for &(o, e) in rest {
        statistic += (o - e) * (o - e) / e;
        n_cells += 1;
    }
    if pooled_cells > 0 {
        statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        n_cells += 1;
    }

    if n_cells < 2 {
        return Chi2Result {
            statistic,
            dof: 0,
            p_value: 0.0,
            pooled_cells,
            pdf_integral: None,
            message: Some(format!(
                "only {n_cells} cell(s) left after pooling cells with expected count < \
                 {min_expected}: the test has no power (use more samples)"
            )),
        };
    }

    let dof = n_cells - 1;
    let p_value = ChiSquared::new(dof as f64)
        .expect("dof >= 1 is a valid chi-square parameter")
        .sf(statistic);
    Chi2Result {
        statistic,
        dof,
        p_value,
        pooled_cells,
        pdf_integral: None,
        message: None,
    }
}

/// Šidák-corrected per-test significance level: running `n_tests` independent tests at this
/// level rejects at least one of them with probability `alpha` when all null hypotheses hold.
/// Equals `1 - (1 - alpha)^(1 / n_tests)` (computed without cancellation).
///
/// # Panics
/// If `n_tests == 0` or `alpha` is not in `[0, 1]`.
pub fn sidak_alpha(alpha: f64, n_tests: usize) -> f64 {
    assert!(n_tests > 0, "sidak_alpha: n_tests must be at least 1");
    assert!(
        (0.0..=1.0).contains(&alpha),
        "sidak_alpha: alpha must be in [0, 1], got {alpha}"
    );
    -((-alpha).ln_1p() / n_tests as f64).exp_m1()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn textbook_die_table() {
        // A die rolled 60 times: the classic example, X^2 = 13.4 with 5 dof, p ~ 0.0199.
        let observed = [5.0, 8.0, 9.0, 8.0, 10.0, 20.0];
        let expected = [10.0; 6];
        let r = chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED);
        assert!(close(r.statistic, 13.4, 1e-12), "{r}");
        assert_eq!(r.dof, 5);
        assert_eq!(r.pooled_cells, 0);
        assert!(r.message.is_none());
        // Closed form for odd dof: sf(x; 5) = erfc(sqrt(x/2)) + sqrt(2x/pi) e^{-x/2} (1 + x/3).
        assert!(close(r.p_value, 0.019905220334774376, 1e-8), "{r}");
        assert!(!r.passes(0.05) && r.passes(0.01));
    }

    #[test]
    fn textbook_critical_values() {
        // 3.841458820694124 is the 95% quantile of chi2 with 1 dof: two cells of 50 expected,
        // each off by sqrt(3.84 * 25), give exactly that statistic and p = 0.05.
        let d = (3.841458820694124f64 * 25.0).sqrt();
        let r = chi2_test(&[50.0 + d, 50.0 - d], &[50.0, 50.0], 5.0);
        assert_eq!(r.dof, 1);
        assert!(close(r.statistic, 3.841458820694124, 1e-12), "{r}");
        assert!(close(r.p_value, 0.05, 1e-9), "{r}");
        // 2 dof: sf(x) = exp(-x/2) exactly.
        let r = chi2_test(&[12.0, 30.0, 58.0], &[20.0, 30.0, 50.0], 5.0);
        let x: f64 = 64.0 / 20.0 + 64.0 / 50.0;
        assert!(close(r.statistic, x, 1e-12));
        assert_eq!(r.dof, 2);
        assert!(close(r.p_value, (-x / 2.0).exp(), 1e-10), "{r}");
    }

    #[test]
    fn pooling_of_small_cells() {
        // Small cells 0.5, 1, 1, 1, 2 (sum 5.5 >= 5) become one pooled cell.
        let observed = [95.0, 104.0, 0.0, 2.0, 1.0, 1.0, 3.0];
        let expected = [100.0, 100.0, 1.0, 1.0, 1.0, 0.5, 2.0];
        let r = chi2_test(&observed, &expected, 5.0);
        assert_eq!(r.pooled_cells, 5);
        assert_eq!(r.dof, 2, "3 cells after pooling");
        let want = 25.0 / 100.0 + 16.0 / 100.0 + (7.0f64 - 5.5).powi(2) / 5.5;
        assert!(close(r.statistic, want, 1e-12), "{r}");

        // The pool (1 + 1 = 2) is still below 5: merged into the smallest big cell (50).
        let r = chi2_test(&[90.0, 55.0, 3.0, 0.0], &[100.0, 50.0, 1.0, 1.0], 5.0);
        assert_eq!(r.pooled_cells, 3);
        assert_eq!(r.dof, 1);
        let want = 100.0 / 100.0 + (58.0f64 - 52.0).powi(2) / 52.0;
        assert!(close(r.statistic, want, 1e-12), "{r}");

        // No pooling needed.
        let r = chi2_test(&[5.0, 7.0], &[6.0, 6.0], 5.0);
        assert_eq!(r.pooled_cells, 0);
        assert_eq!(r.dof, 1);
    }

    #[test]
    fn zero_expectation_cells() {
        // Empty impossible cells are ignored: they add no degrees of freedom.
        let r = chi2_test(&[48.0, 0.0, 52.0, 0.0], &[50.0, 0.0, 50.0, 0.0], 5.0);
        assert_eq!(r.dof, 1);
        assert_eq!(r.pooled_cells, 0);
        assert!(r.passes(0.5), "{r}");
        // A single sample where the pdf says none can be: immediate failure.
        let r = chi2_test(&[48.0, 1.0, 51.0], &[50.0, 0.0, 50.0], 5.0);
        assert_eq!(r.p_value, 0.0);
        assert!(
            r.message.as_deref().unwrap().contains("expected count 0"),
            "{r}"
        );
        assert!(!r.passes(1e-300));
    }

    #[test]
    fn invalid_and_powerless_inputs_fail() {
        let r = chi2_test(&[1.0, 2.0], &[1.5, f64::NAN], 5.0);
        assert_eq!(r.p_value, 0.0);
        assert!(r.message.is_some());
        let r = chi2_test(&[1.0, 2.0], &[4.0, -1.0], 5.0);
        assert_eq!(r.p_value, 0.0);
        // Everything pooled into one cell: no degrees of freedom, the test cannot pass.
        let r = chi2_test(&[1.0, 2.0, 1.0], &[1.0, 1.0, 2.0], 5.0);
        assert_eq!(r.dof, 0);
        assert_eq!(r.p_value, 0.0);
        assert!(r.message.as_deref().unwrap().contains("no power"), "{r}");
    }

    #[test]
    fn sidak_correction() {
        assert!(close(sidak_alpha(0.01, 1), 0.01, 1e-14));
        assert!(close(sidak_alpha(0.01, 10), 0.0010045287082499632, 1e-12));
        // Tiny alphas keep their precision (no 1 - (1 - x) cancellation).
        assert!(close(sidak_alpha(1e-12, 1000), 1e-15, 1e-6));
        // n tests at the corrected level have overall level alpha.
        let a = sidak_alpha(0.05, 7);
        assert!(close(1.0 - (1.0 - a).powi(7), 0.05, 1e-12));
    }
}

//! What a test file's cases report: one line each with its p-value and verdict, and the
//! settings every kind of case shares.
use crate::stats::{Chi2Result, TTest};
use std::fmt;

/// The surface point `uv` at which BSDFs are tested (textures are evaluated there).
pub const TEST_UV: [f32; 2] = [0.5, 0.5];

/// Smallest accepted `significanceLevel`: below it a test can hardly fail and is useless.
pub const MIN_SIGNIFICANCE: f64 = 1e-6;

/// Smallest accepted `sampleCount` of a t-test (the test leans on the central limit theorem).
pub(crate) const MIN_TTEST_SAMPLES: i64 = 100;

/// One t-tested case (a scene, or a BSDF at one incident angle).
#[derive(Clone, Debug)]
pub struct CaseResult {
    /// What was tested (the object, its position in the file, the incident direction).
    pub label: String,
    /// Sample mean of the luminance.
    pub mean: f64,
    /// The reference value.
    pub reference: f64,
    /// The test.
    pub test: TTest,
    /// The per-case (Šidák-corrected) significance level.
    pub alpha: f64,
    /// Whether the case passed at `alpha`.
    pub passed: bool,
}

/// One chi-square case (a BSDF at one incident direction).
#[derive(Clone, Debug)]
pub struct Chi2Case {
    /// What was tested (the BSDF, its position in the file, the incident direction).
    pub label: String,
    /// The test.
    pub result: Chi2Result,
    /// The per-case (Šidák-corrected) significance level.
    pub alpha: f64,
    /// Whether the case passed at `alpha`.
    pub passed: bool,
}

/// A case of any test type.
#[derive(Clone, Debug)]
pub enum Case {
    /// A t-test of a mean.
    Mean(CaseResult),
    /// A chi-square test of a distribution.
    Chi2(Chi2Case),
}

impl Case {
    /// Whether the case passed.
    pub fn passed(&self) -> bool {
        match self {
            Case::Mean(c) => c.passed,
            Case::Chi2(c) => c.passed,
        }
    }

    /// What was tested.
    pub fn label(&self) -> &str {
        match self {
            Case::Mean(c) => &c.label,
            Case::Chi2(c) => &c.label,
        }
    }

    /// The case's p-value.
    pub fn p_value(&self) -> f64 {
        match self {
            Case::Mean(c) => c.test.p_value,
            Case::Chi2(c) => c.result.p_value,
        }
    }
}

/// A p-value for people: four decimals, or scientific notation when that would show 0.
fn fmt_p(p: f64) -> String {
    if p == 0.0 || p >= 1e-4 || p.is_nan() {
        format!("{p:.4}")
    } else {
        format!("{p:.2e}")
    }
}

impl fmt::Display for Case {
    /// The one-line report of `tessera test`:
    /// `LABEL: mean M vs reference R, p = P PASS` or `LABEL: chi2 = X, dof = D, p = P PASS`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let verdict = if self.passed() { "PASS" } else { "FAIL" };
        match self {
            Case::Mean(c) => write!(
                f,
                "{}: mean {:.6} vs reference {:.6}, p = {} {verdict}",
                c.label,
                c.mean,
                c.reference,
                fmt_p(c.test.p_value)
            ),
            Case::Chi2(c) => {
                let r = &c.result;
                write!(
                    f,
                    "{}: chi2 = {:.2}, dof = {}, p = {} {verdict}",
                    c.label,
                    r.statistic,
                    r.dof,
                    fmt_p(r.p_value)
                )?;
                if let Some(m) = &r.message {
                    write!(f, " ({m})")?;
                }
                Ok(())
            }
        }
    }
}

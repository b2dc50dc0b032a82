//! Nori-style test files, run by `tessera test FILE.xml`: a root `<test>` element whose
//! parameters use Nori's names (`significanceLevel`, `sampleCount`...; the Nori dialect turns
//! them into `significance_level`, `sample_count`, and either spelling is accepted).
//!
//! - `<test type="ttest">` with `<scene>` children ([`scene_ttest`]): each scene's mean
//!   luminance over random camera rays against its reference.
//! - `<test type="ttest">` with `<bsdf>` children ([`bsdf_ttest`]): each BSDF's mean sampled
//!   weight (its directional albedo, as luminance) at each of the `angles` against its
//!   reference.
//! - `<test type="chi2test">` with `<bsdf>` children ([`chi2test`]): each BSDF's `sample`
//!   against its `pdf` at `testCount` random incident directions.
//!
//! All cases of a file share one overall significance level, split by the Šidák correction,
//! so a correct implementation fails a file with probability `significanceLevel`. Random
//! streams are keyed by the command's `--seed`, so a run is reproducible.
//!
//! Bad input (a missing or malformed list, a count mismatch, an unknown parameter, a parameter
//! out of range, a BSDF that cannot be built) is an [`InputError`] located at the offending
//! element or property.

pub mod bsdf_ttest;
pub mod chi2test;
pub mod scene_ttest;

use std::fmt;

use crate::stats::{Chi2Result, TTest};
use tessera_scene::error::{InputError, Loc};
use tessera_scene::xml::{Kind, Object};

/// The surface point `uv` at which BSDFs are tested (textures are evaluated there).
pub const TEST_UV: [f32; 2] = [0.5, 0.5];

/// Smallest accepted `significanceLevel`: below it a test can hardly fail and is useless.
pub const MIN_SIGNIFICANCE: f64 = 1e-6;

/// Smallest accepted `sampleCount` of a t-test (the test leans on the central limit theorem).
pub const MIN_TTEST_SAMPLES: i64 = 100;

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

/// Runs every case of a test file (already loaded; see the module docs for the types),
/// calling `report` after each; `seed` keys the random streams.
pub fn run_test_file(
    root: &Object,
    seed: u64,
    mut report: impl FnMut(&Case),
) -> Result<Vec<Case>, InputError> {
    if root.kind != Kind::Test {
        return Err(root.error("a test file's root element must be <test>"));
    }
    match root.plugin.as_str() {
        "ttest" => {
            let mut cases = Vec::new();
            let wrap = |c: &CaseResult| {
                let c = Case::Mean(c.clone());
                report(&c);
                cases.push(c);
            };
            run_ttest(root, seed, wrap)?;
            Ok(cases)
        }
        "chi2test" => chi2test::run(root, seed, report),
        other => Err(root.error(format!(
            "unknown test type \"{other}\" (known: ttest, chi2test)"
        ))),
    }
}

/// Runs a `<test type="ttest">` file (scenes or BSDFs); `chi2test` files need
/// [`run_test_file`].
pub fn run_test_object(
    root: &Object,
    seed: u64,
    report: impl FnMut(&CaseResult),
) -> Result<Vec<CaseResult>, InputError> {
    if root.kind != Kind::Test {
        return Err(root.error("a test file's root element must be <test>"));
    }
    if root.plugin != "ttest" {
        return Err(root.error(format!(
            "run_test_object runs ttest files, not \"{}\" (use run_test_file)",
            root.plugin
        )));
    }
    run_ttest(root, seed, report)
}

/// A ttest of scenes or of BSDFs, by what the children are.
fn run_ttest(
    root: &Object,
    seed: u64,
    report: impl FnMut(&CaseResult),
) -> Result<Vec<CaseResult>, InputError> {
    let first = root.children.first().map(|c| c.obj.kind);
    if first == Some(Kind::Bsdf) {
        bsdf_ttest::run(root, seed, report)
    } else {
        scene_ttest::run(root, seed, report)
    }
}

/// The location of property `name` of `obj`, or of `obj` itself when absent.
pub(crate) fn prop_loc(obj: &Object, name: &str) -> Loc {
    obj.props
        .iter()
        .find(|p| p.name == name)
        .map_or_else(|| obj.loc.clone(), |p| p.loc.clone())
}

/// An error located at property `name` of `obj` (or at `obj` when absent).
pub(crate) fn at_prop(obj: &Object, name: &str, msg: impl Into<String>) -> InputError {
    InputError::at(&prop_loc(obj, name), msg)
}

/// `significanceLevel` (default 0.01), in `[MIN_SIGNIFICANCE, 1)`.
pub(crate) fn significance(root: &Object) -> Result<f64, InputError> {
    let level = root.float("significance_level", 0.01)?;
    if !(MIN_SIGNIFICANCE..1.0).contains(&level) {
        return Err(at_prop(
            root,
            "significance_level",
            format!(
                "\"significanceLevel\" must be at least {MIN_SIGNIFICANCE:e} and below 1, \
                 found {level}"
            ),
        ));
    }
    Ok(level)
}

/// An integer parameter with a default, at least `min`.
pub(crate) fn count(
    root: &Object,
    name: &str,
    nori_name: &str,
    default: i64,
    min: i64,
) -> Result<usize, InputError> {
    let v = root.integer(name, default)?;
    if v < min {
        return Err(at_prop(
            root,
            name,
            format!("\"{nori_name}\" must be at least {min}, found {v}"),
        ));
    }
    usize::try_from(v).map_err(|_| at_prop(root, name, format!("\"{nori_name}\" is too large")))
}

/// A required list of numbers in a string parameter (separated by commas and/or white space,
/// as Nori tokenizes), with the location of the property.
pub(crate) fn number_list(
    root: &Object,
    name: &str,
    nori_name: &str,
) -> Result<(Vec<f64>, Loc), InputError> {
    let text = root
        .string_opt(name)?
        .ok_or_else(|| root.missing(nori_name))?;
    let loc = prop_loc(root, name);
    let values: Vec<f64> = text
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(InputError::at(
                &loc,
                format!("\"{nori_name}\" holds \"{s}\", not a finite number"),
            )),
        })
        .collect::<Result<_, _>>()?;
    if values.is_empty() {
        return Err(InputError::at(&loc, format!("\"{nori_name}\" is empty")));
    }
    Ok((values, loc))
}

/// The `<bsdf>` children of a BSDF test, built, with labels (`diffuse (file:line:col)`);
/// any other child is a located error.
pub(crate) fn bsdf_children(
    root: &Object,
) -> Result<Vec<(String, tessera_core::bsdf::Bsdf)>, InputError> {
    let mut out = Vec::new();
    for c in &root.children {
        if c.obj.kind != Kind::Bsdf {
            return Err(InputError::at(
                &c.loc,
                format!(
                    "a BSDF {} holds <bsdf> elements only, found <{}>",
                    root.plugin,
                    c.obj.kind.tag()
                ),
            ));
        }
        c.mark_used();
        let bsdf = tessera_scene::build_bsdf_object(&c.obj)?;
        out.push((format!("{} ({})", c.obj.plugin, c.loc), bsdf));
    }
    if out.is_empty() {
        return Err(root.error(format!("the {} holds no <bsdf>", root.plugin)));
    }
    Ok(out)
}

/// `(x, y, z)` with four decimals, for labels.
pub(crate) fn fmt_dir(v: glam::Vec3) -> String {
    format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z)
}

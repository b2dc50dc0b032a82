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
pub mod case;
pub mod chi2test;
mod read;
pub mod scene_ttest;

pub use case::{Case, CaseResult, Chi2Case, MIN_SIGNIFICANCE, TEST_UV};
use tessera_scene::error::InputError;
use tessera_scene::xml::{Kind, Object};

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

//! `<test type="chi2test">` with `<bsdf>` children: each BSDF's `sample` against its `pdf`, as
//! Nori's `ChiSquareTest` does, with [`BsdfChi2`] (delta components and the per-sample
//! `eval`/`pdf` consistency checks included).
//!
//! Parameters (Nori's names and defaults):
//! - `significanceLevel` (float, default 0.01): split over all cases (BSDFs x `testCount`) by
//!   the Šidák correction.
//! - `resolution` (integer, default 10, at least 2): cells in `cos θ` over `[-1, 1]`; `φ` gets
//!   twice as many.
//! - `sampleCount` (integer, default `resolution * 2 resolution * 5000` = 1e6): samples per
//!   case; on average at least `10 * minExpFrequency` per cell, or the test has no power.
//! - `testCount` (integer, default 5): incident directions per BSDF, drawn cosine-weighted on
//!   the upper hemisphere as in Nori (from a stream keyed by `--seed`).
//! - `minExpFrequency` (integer, default 5): cells expecting fewer samples are pooled. The
//!   BSDF chi-square harness pools at 5; other values are rejected.
//! - `bothSides` (boolean, default false; a Tessera extension): every second incident
//!   direction is mirrored below the surface, for two-sided models and glass.
//!
//! BSDFs are tested at `uv = TEST_UV`.
use super::case::{Case, Chi2Case, TEST_UV};
use super::read::{at_prop, bsdf_children, count, fmt_dir, significance};
use crate::stats::{sidak_alpha, BsdfChi2, Chi2Result, Pcg32, DEFAULT_MIN_EXPECTED};
use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_core::sampling::warp::square_to_cosine_hemisphere;
use tessera_scene::error::InputError;
use tessera_scene::xml::Object;

/// Samples per cell of Nori's automatic `sampleCount`.
const NORI_SAMPLES_PER_CELL: i64 = 5000;

/// Fewest samples per cell on average, in units of `minExpFrequency`.
const MIN_MEAN_PER_CELL: usize = 10;

/// One planned case.
#[derive(Clone, Debug)]
pub struct Chi2Spec {
    /// Index of the BSDF in [`Chi2Plan::bsdfs`].
    pub bsdf: usize,
    /// Incident direction.
    pub wi: Vec3,
    /// Seed of the sample stream.
    pub seed: u64,
    /// Report label.
    pub label: String,
}

/// A parsed and validated chi2test file.
#[derive(Clone, Debug)]
pub struct Chi2Plan {
    /// The BSDFs, with their labels.
    pub bsdfs: Vec<(String, Bsdf)>,
    /// Every case, BSDF-major.
    pub cases: Vec<Chi2Spec>,
    /// Cells and samples of each case.
    pub config: BsdfChi2,
    /// Per-case (Šidák-corrected) significance level.
    pub alpha: f64,
}

/// Reads and checks a chi2test file; `seed` keys the incident directions and sample streams.
pub fn plan(root: &Object, seed: u64) -> Result<Chi2Plan, InputError> {
    let level = significance(root)?;
    let res = count(root, "resolution", "resolution", 10, 2)?;
    let cells = 2 * res * res;
    let min_exp = count(root, "min_exp_frequency", "minExpFrequency", 5, 1)?;
    if min_exp as f64 != DEFAULT_MIN_EXPECTED {
        return Err(at_prop(
            root,
            "min_exp_frequency",
            format!(
                "\"minExpFrequency\" = {min_exp} is not supported: the BSDF chi-square test \
                 pools cells expecting fewer than {DEFAULT_MIN_EXPECTED} samples"
            ),
        ));
    }
    let auto = (cells as i64).saturating_mul(NORI_SAMPLES_PER_CELL);
    let samples = count(root, "sample_count", "sampleCount", auto, 1)?;
    let need = cells * MIN_MEAN_PER_CELL * min_exp;
    if samples < need {
        return Err(at_prop(
            root,
            "sample_count",
            format!(
                "too few samples: \"sampleCount\" = {samples} over {cells} cells (resolution \
                 {res}) is {:.1} per cell on average; at least {} per cell ({need} samples) \
                 are needed for the test to have power",
                samples as f64 / cells as f64,
                MIN_MEAN_PER_CELL * min_exp
            ),
        ));
    }
    let test_count = count(root, "test_count", "testCount", 5, 1)?;
    let both_sides = root.boolean("both_sides", false)?;
    let bsdfs = bsdf_children(root)?;
    root.check_unused()?;

    let mut dirs = Pcg32::new(seed ^ 0xC412_7E57);
    let mut cases = Vec::new();
    for (b, (label, _)) in bsdfs.iter().enumerate() {
        for l in 0..test_count {
            let mut wi = square_to_cosine_hemisphere(dirs.next_vec2());
            if both_sides && l % 2 == 1 {
                wi.z = -wi.z;
            }
            let k = cases.len() as u64;
            cases.push(Chi2Spec {
                bsdf: b,
                wi,
                seed: seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ k.wrapping_add(0xC412),
                label: format!("{label} wi={}", fmt_dir(wi)),
            });
        }
    }
    Ok(Chi2Plan {
        alpha: sidak_alpha(level, cases.len()),
        bsdfs,
        cases,
        config: BsdfChi2 {
            theta_bins: res,
            phi_bins: 2 * res,
            samples,
        },
    })
}

/// Runs the planned cases with `test(bsdf, wi, seed)` (normally [`BsdfChi2::run`]), calling
/// `report` after each.
pub(crate) fn execute(
    plan: &Chi2Plan,
    mut test: impl FnMut(&Bsdf, Vec3, u64) -> Chi2Result,
    mut report: impl FnMut(&Case),
) -> Vec<Case> {
    let mut out = Vec::with_capacity(plan.cases.len());
    for spec in &plan.cases {
        let result = test(&plan.bsdfs[spec.bsdf].1, spec.wi, spec.seed);
        let case = Case::Chi2(Chi2Case {
            label: spec.label.clone(),
            passed: result.passes(plan.alpha),
            alpha: plan.alpha,
            result,
        });
        report(&case);
        out.push(case);
    }
    out
}

/// Runs every case of a chi2test file.
pub fn run(root: &Object, seed: u64, report: impl FnMut(&Case)) -> Result<Vec<Case>, InputError> {
    let plan = plan(root, seed)?;
    let uv = Vec2::from(TEST_UV);
    let config = plan.config;
    Ok(execute(
        &plan,
        |bsdf, wi, s| config.run(bsdf, wi, uv, s),
        report,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::SphereChi2;
    use std::path::Path;
    use tessera_core::math::Norm;

    fn load(text: &str) -> Object {
        tessera_scene::xml::load_str(text, Path::new("chi2.xml"), &[]).expect("loads")
    }

    const FILE: &str = r#"<test type="chi2test">
  <integer name="sampleCount" value="200000"/>
  <integer name="testCount" value="3"/>
  <boolean name="bothSides" value="true"/>
  <bsdf type="diffuse"/>
  <bsdf type="twosided"><bsdf type="diffuse"/></bsdf>
</test>"#;

    #[test]
    fn plan_follows_nori() {
        let p = plan(&load(FILE), 0).unwrap();
        assert_eq!(p.cases.len(), 6);
        assert_eq!((p.config.theta_bins, p.config.phi_bins), (10, 20));
        assert!((p.alpha - sidak_alpha(0.01, 6)).abs() < 1e-15);
        for (i, c) in p.cases.iter().enumerate() {
            assert!((c.wi.norm() - 1.0).abs() < 1e-5, "{c:?}");
            // bothSides mirrors every second direction below the surface.
            assert_eq!(c.wi.z < 0.0, i % 3 == 1, "{c:?}");
        }
        // The automatic sample count is Nori's: 5000 per cell.
        let p = plan(
            &load("<test type=\"chi2test\"><bsdf type=\"diffuse\"/></test>"),
            0,
        );
        assert_eq!(p.unwrap().config.samples, 1_000_000);
    }

    #[test]
    fn runner_passes_the_right_pdf_and_fails_a_wrong_one() {
        let p = plan(&load(FILE), 0).unwrap();
        let uv = Vec2::from(TEST_UV);
        // The one-sided diffuse seen from below scatters nothing: that case cannot pass.
        let cases = execute(&p, |b, wi, s| p.config.run(b, wi, uv, s), |_| {});
        let passed: Vec<bool> = cases.iter().map(Case::passed).collect();
        assert_eq!(passed, [true, false, true, true, true, true], "{cases:#?}");

        // A wrapper around the same sampler that claims a cos^1.15 lobe (normalized, so only
        // its shape is wrong, by little): every case must fail.
        let n = 1.15f64;
        let wrong = |b: &Bsdf, wi: Vec3, s: u64| {
            let chi2 = SphereChi2 {
                theta_bins: 10,
                phi_bins: 20,
                samples: 200_000,
            };
            let side = wi.z.signum() as f64;
            chi2.run(
                |u| b.sample(wi, 0.5, u, uv).map(|x| x.wo),
                |w| {
                    let z = f64::from(w.z) * side;
                    if z > 0.0 {
                        (n + 1.0) / std::f64::consts::TAU * z.powf(n)
                    } else {
                        0.0
                    }
                },
                s,
            )
        };
        let mut lines = Vec::new();
        let cases = execute(&p, wrong, |c| lines.push(c.to_string()));
        assert!(cases.iter().all(|c| !c.passed()), "{lines:#?}");
        assert!(lines
            .iter()
            .all(|l| l.ends_with("FAIL") || l.contains("FAIL (")));
    }
}

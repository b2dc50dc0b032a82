//! `<test type="ttest">` with `<bsdf>` children: the directional albedo of each BSDF at each
//! incident angle, as Nori's `StudentsTTest` does.
//!
//! Parameters:
//! - `angles` (string, required): incident angles in degrees, in `[0, 180]`; angle `θ` means
//!   `wi = (sin θ, 0, cos θ)` in the local frame (Nori's `sphericalDirection(θ, 0)`; above 90
//!   degrees `wi` is below the surface).
//! - `references` (string, required): one reference per BSDF and angle, BSDF-major (all angles
//!   of the first BSDF, then of the second...), as in Nori: the luminance (Nori's weights) of
//!   the expected sampled weight, i.e. of the directional albedo.
//! - `sampleCount` (integer, default 100000, at least 100): `sample` calls per case.
//! - `significanceLevel` (float, default 0.01): split over all cases by the Šidák correction.
//!
//! Each case runs [`albedo_t_test`] at `uv = TEST_UV`: the mean luminance of the sampled
//! weights (a failed sample counts 0) against the reference; a deterministic weight (zero
//! variance) must match the reference within f32 rounding.
use super::case::{CaseResult, MIN_TTEST_SAMPLES, TEST_UV};
use super::read::{bsdf_children, count, fmt_dir, number_list, significance};
use crate::stats::{albedo_t_test, sidak_alpha, AlbedoReference};
use glam::{Vec2, Vec3};
use tessera_scene::error::InputError;
use tessera_scene::xml::Object;

/// `wi` for an incident angle in degrees (Nori's `sphericalDirection(θ, 0)`).
pub(crate) fn incident_direction(degrees: f64) -> Vec3 {
    let t = degrees.to_radians();
    Vec3::new(t.sin() as f32, 0.0, t.cos() as f32)
}

/// Seed of case `case` for the run seed `seed`.
fn case_seed(seed: u64, case: usize) -> u64 {
    seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (case as u64).wrapping_add(0x5EED_0A1B)
}

/// Runs every BSDF case of a ttest file; `seed` keys the random streams.
pub fn run(
    root: &Object,
    seed: u64,
    mut report: impl FnMut(&CaseResult),
) -> Result<Vec<CaseResult>, InputError> {
    let (angles, angles_loc) = number_list(root, "angles", "angles")?;
    if let Some(a) = angles.iter().find(|a| !(0.0..=180.0).contains(*a)) {
        return Err(InputError::at(
            &angles_loc,
            format!("\"angles\" holds {a}: incident angles are degrees in [0, 180]"),
        ));
    }
    let (references, refs_loc) = number_list(root, "references", "references")?;
    let level = significance(root)?;
    let samples = count(
        root,
        "sample_count",
        "sampleCount",
        100_000,
        MIN_TTEST_SAMPLES,
    )?;
    let bsdfs = bsdf_children(root)?;
    if references.len() != bsdfs.len() * angles.len() {
        return Err(InputError::at(
            &refs_loc,
            format!(
                "{} references for {} bsdf(s) x {} angle(s): one per bsdf and angle, bsdf-major",
                references.len(),
                bsdfs.len(),
                angles.len()
            ),
        ));
    }
    root.check_unused()?;
    let alpha = sidak_alpha(level, references.len());
    let uv = Vec2::from(TEST_UV);
    let mut out = Vec::with_capacity(references.len());
    let mut refs = references.iter();
    for (label, bsdf) in &bsdfs {
        for &angle in &angles {
            let reference = *refs.next().expect("counts checked");
            let wi = incident_direction(angle);
            let r = albedo_t_test(
                bsdf,
                wi,
                uv,
                AlbedoReference::Luminance(reference),
                samples,
                case_seed(seed, out.len()),
            );
            let case = CaseResult {
                label: format!("{label} angle={angle} wi={}", fmt_dir(wi)),
                mean: r.means[0],
                reference,
                test: r.test,
                alpha,
                passed: r.passes(alpha),
            };
            report(&case);
            out.push(case);
        }
    }
    Ok(out)
}

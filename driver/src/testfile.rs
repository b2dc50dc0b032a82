//! Nori-style test files: `<test type="ttest">` with one `<scene>` per reference value.
//!
//! Parameters of `<test type="ttest">`: `references` (string, comma/space separated floats, one
//! per scene, required), `significanceLevel` / `significance_level` (float, default 0.01, split
//! over the cases by the Sidak correction), `sampleCount` / `sample_count` (integer, default
//! 100000). As in Nori, each scene is tested by tracing `sample_count` camera rays through
//! uniformly random image positions (no pixel filter) with the scene's integrator, taking the
//! luminance of each, and testing the mean against the reference with Student's t-test (with a
//! floor of 4 f32 ulps on the standard error: the renderer computes in single precision).
//! BSDF t-tests and `chi2test` files belong to the material set and are reported as unsupported.
use crate::error::InputError;
use crate::scene::build_scene_object;
use crate::stats::{sidak_alpha, Moments, TTest};
use crate::xml::{Kind, Object};
use tessera_core::glam::Vec2;
use tessera_core::sampling::{IndependentSampler, Sampler};

/// One tested case.
#[derive(Clone, Debug)]
pub struct CaseResult {
    /// What was tested (integrator and position in the file).
    pub label: String,
    /// Sample mean of the luminance.
    pub mean: f64,
    /// The reference value.
    pub reference: f64,
    /// The test.
    pub test: TTest,
    /// Whether the case passed at the corrected significance.
    pub passed: bool,
}

/// Nori's luminance weights.
fn luminance(c: tessera_core::Color) -> f64 {
    0.212671 * c.x as f64 + 0.715160 * c.y as f64 + 0.072169 * c.z as f64
}

/// Runs every case of a test file (already loaded); `seed` keys the random streams.
pub fn run_test_object(
    root: &Object,
    seed: u64,
    mut report: impl FnMut(&CaseResult),
) -> Result<Vec<CaseResult>, InputError> {
    if root.kind != Kind::Test {
        return Err(root.error("a test file's root element must be <test>"));
    }
    if root.plugin != "ttest" {
        return Err(root.error(format!(
            "test type \"{}\" is not supported yet (ttest is)",
            root.plugin
        )));
    }
    let refs_text = root
        .string_opt("references")?
        .ok_or_else(|| root.missing("references"))?;
    let references: Vec<f64> = refs_text
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<f64>()
                .map_err(|_| root.error(format!("\"references\" holds \"{s}\", not a number")))
        })
        .collect::<Result<_, _>>()?;
    let level = root.float("significance_level", 0.01)?;
    let samples = root.integer("sample_count", 100_000)?;
    if !(level > 0.0 && level < 1.0) || samples < 2 {
        return Err(root.error("significance_level must be in (0, 1) and sample_count at least 2"));
    }
    let scenes: Vec<_> = root
        .children
        .iter()
        .filter(|c| c.obj.kind == Kind::Scene)
        .collect();
    if let Some(c) = root.children.iter().find(|c| c.obj.kind != Kind::Scene) {
        return Err(InputError::at(
            &c.loc,
            format!(
                "{} t-tests are not supported yet (scene t-tests are)",
                c.obj.kind
            ),
        ));
    }
    if scenes.len() != references.len() {
        return Err(root.error(format!(
            "{} references for {} scenes",
            references.len(),
            scenes.len()
        )));
    }
    for c in &scenes {
        c.mark_used();
    }
    root.check_unused()?;
    let alpha = sidak_alpha(level, scenes.len());
    let mut out = Vec::new();
    for (i, (child, &reference)) in scenes.iter().zip(&references).enumerate() {
        let loaded = build_scene_object(&child.obj)?;
        let (scene, integrator) = (&loaded.scene, &loaded.integrator);
        let (w, h) = (scene.camera.width as f32, scene.camera.height as f32);
        let mut m = Moments::new();
        for k in 0..samples as u64 {
            let mut s = IndependentSampler::new(seed, i as u32, 0, k);
            let pos = s.next_2d() * Vec2::new(w, h);
            let ray = scene.camera.generate_ray(pos);
            m.push(luminance(integrator.li(scene, ray, &mut s)));
        }
        let test = crate::stats::t_test_mean_f32(&m, reference);
        let label = format!(
            "scene {} ({}) at {}",
            i + 1,
            loaded.integrator_spec.name,
            child.loc
        );
        let r = CaseResult {
            label,
            mean: m.mean(),
            reference,
            passed: test.passes(alpha),
            test,
        };
        report(&r);
        out.push(r);
    }
    Ok(out)
}

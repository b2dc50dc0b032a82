//! `<test type="ttest">` with one `<scene>` per reference value (the Wakame assignment's form).
//!
//! Parameters: `references` (string, comma/space separated floats, one per scene, required),
//! `significanceLevel` (float, default 0.01, split over the cases by the Šidák correction),
//! `sampleCount` (integer, default 100000, at least 100). As in Nori, each scene is tested by
//! tracing `sampleCount` camera rays through uniformly random image positions (no pixel filter)
//! with the scene's integrator, taking the luminance of each, and testing the mean against the
//! reference with Student's t-test (with a floor of 4 f32 ulps on the standard error: the
//! renderer computes in single precision).
use super::case::{CaseResult, MIN_TTEST_SAMPLES};
use super::read::{count, number_list, significance};
use crate::stats::{luminance, sidak_alpha, t_test_mean_f32, Moments};
use tessera_core::glam::Vec2;
use tessera_core::sampling::{IndependentSampler, Sampler};
use tessera_scene::build_scene_object;
use tessera_scene::error::InputError;
use tessera_scene::xml::{Kind, Object};

/// Runs every scene case of a ttest file; `seed` keys the random streams.
pub fn run(
    root: &Object,
    seed: u64,
    mut report: impl FnMut(&CaseResult),
) -> Result<Vec<CaseResult>, InputError> {
    let (references, refs_loc) = number_list(root, "references", "references")?;
    let level = significance(root)?;
    let samples = count(
        root,
        "sample_count",
        "sampleCount",
        100_000,
        MIN_TTEST_SAMPLES,
    )?;
    if let Some(c) = root.children.iter().find(|c| c.obj.kind != Kind::Scene) {
        return Err(InputError::at(
            &c.loc,
            format!(
                "a ttest holds either <scene> or <bsdf> elements, found <{}> among scenes",
                c.obj.kind.tag()
            ),
        ));
    }
    let scenes: Vec<_> = root.children.iter().collect();
    if scenes.is_empty() {
        return Err(root.error("the ttest holds no <scene> (nor <bsdf>)"));
    }
    if scenes.len() != references.len() {
        return Err(InputError::at(
            &refs_loc,
            format!(
                "{} references for {} scenes (one per scene)",
                references.len(),
                scenes.len()
            ),
        ));
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
            let ray = scene.camera.sample_ray(pos, &mut s);
            m.push(luminance(integrator.li(scene, ray, &mut s).as_dvec3()));
        }
        let test = t_test_mean_f32(&m, reference);
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
            alpha,
            test,
        };
        report(&r);
        out.push(r);
    }
    Ok(out)
}

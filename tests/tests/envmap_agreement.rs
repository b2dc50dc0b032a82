//! The environment-lit scene (`scenes/envmap.xml`: diffuse spheres under a latitude-longitude
//! sky with a small sun), rendered by the path integrators and by Mitsuba 3, agrees region by
//! region: the test of the envmap's mapping, rotation, bilinear lookup and importance sampling
//! together, in the way of `cbox_agreement.rs`.
//!
//! Regions are 8x8-pixel blocks; each region's mean and its variance (pixels as strata) give a
//! z statistic for a difference of two renders. Significance 0.01, Sidak-corrected over all
//! regions, channels and pairs of a test.
use tessera::image_io::read_image;
use tessera::render::Framebuffer;
use tessera_lab::stats::sidak_alpha;
use tessera_tests::{
    load_file, region_stats, render_loaded, scenes_dir, worst_against_reference, worst_region,
};

const RES: u32 = 64;
const BLOCK: u32 = 8;
const SCENE: &str = "envmap.xml";

fn render(integrator: &str, spp: u64, seed: u64) -> Framebuffer {
    let mut loaded = load_file(SCENE, &[("res", "64"), ("rfilter", "box")]);
    loaded
        .set_integrator(Some(integrator), None)
        .expect("known integrator");
    render_loaded(&loaded, spp, seed)
}

/// Image mean per channel.
fn image_mean(fb: &Framebuffer) -> [f64; 3] {
    let mut m = [0.0; 3];
    for p in &fb.pixels {
        for (k, v) in m.iter_mut().enumerate() {
            *v += p.sum[k] / p.count as f64 / fb.pixels.len() as f64;
        }
    }
    m
}

/// path_mats, path_ems and path_half agree with path_mis (path_ems counts the sky only through
/// emitter sampling: it needs the map's density to be positive wherever the sky is bright).
/// BSDF sampling finds the sun in under 1% of bounces: with few hits per region the sample
/// variance understates the spread and the z statistic is skewed, so the two integrators that
/// count those hits unweighted by MIS (path_mats, and path_half at weight 1/2) get 4x the samples.
#[test]
fn integrators_agree_on_the_envmap_scene() {
    let spp = 256;
    let reference = render("path_mis", spp, 1);
    let others = [
        ("path_mats", render("path_mats", 4 * spp, 2)),
        ("path_ems", render("path_ems", spp, 3)),
        ("path_half", render("path_half", 4 * spp, 4)),
    ];
    let alpha = sidak_alpha(0.01, others.len() * (RES / BLOCK).pow(2) as usize * 3);
    println!("path_mis: image mean {:.5?}", image_mean(&reference));
    for (name, fb) in &others {
        assert_eq!(fb.dropped() + reference.dropped(), 0);
        let (p, what) = worst_region(fb, RES, BLOCK, |bx, by, k| {
            region_stats(&reference, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
        });
        println!(
            "{name} vs path_mis: image mean {:.5?}, worst p = {p:.3e} at {what}",
            image_mean(fb)
        );
        assert!(
            p >= alpha,
            "{name} vs path_mis: p = {p:.3e} < {alpha:.3e} at {what}"
        );
    }
}

/// Our render agrees with Mitsuba 3's (`scenes/refs/envmap_64x64_mitsuba.exr`, 16384 spp, made
/// by scripts/make_refs.sh). The reference's own variance is estimated as ours scaled by the
/// ratio of sample counts.
#[test]
fn envmap_scene_matches_mitsuba() {
    let spp = 512;
    let ref_spp = 16384.0;
    let ours = render("path_mis", spp, 11);
    assert_eq!(ours.dropped(), 0);
    let reference =
        read_image(&scenes_dir().join("refs/envmap_64x64_mitsuba.exr")).expect("reference image");
    let mut ref_mean = [0.0f64; 3];
    for p in &reference.data {
        for k in 0..3 {
            ref_mean[k] += f64::from(p[k]) / reference.data.len() as f64;
        }
    }
    println!(
        "image mean: Tessera {:.5?}, Mitsuba 3 {:.5?}",
        image_mean(&ours),
        ref_mean
    );
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    // One light: our estimator is the reference's.
    let (p, what) = worst_against_reference(&ours, &ours, spp, &reference, ref_spp, RES, BLOCK);
    println!("envmap: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(
        p >= alpha,
        "envmap: Tessera vs Mitsuba 3: p = {p:.3e} < {alpha:.3e} at {what}"
    );
}

/// Worst region p-value of `loaded` at 512 spp against the Mitsuba reference.
fn worst_against_mitsuba(loaded: &tessera_scene::LoadedScene) -> (f64, String) {
    let ours = render_loaded(loaded, 512, 11);
    let reference =
        read_image(&scenes_dir().join("refs/envmap_64x64_mitsuba.exr")).expect("reference image");
    worst_against_reference(&ours, &ours, 512, &reference, 16384.0, RES, BLOCK)
}

/// The comparison has power: a sky 2% too bright (`env_scale` 1.02) is rejected.
#[test]
fn comparison_rejects_a_two_percent_brighter_sky() {
    let loaded = load_file(
        SCENE,
        &[("res", "64"), ("rfilter", "box"), ("env_scale", "1.02")],
    );
    let (p, what) = worst_against_mitsuba(&loaded);
    println!("sky 2% brighter: worst p = {p:.3e} at {what}");
    assert!(
        p < sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3),
        "a 2% brighter sky went unnoticed (p = {p:.3e})"
    );
}

/// ... and so is the sky turned by 3 degrees about +y (`to_world` 3 degrees off Mitsuba's).
#[test]
fn comparison_rejects_a_turned_sky() {
    let text = std::fs::read_to_string(scenes_dir().join(SCENE)).expect("scene file");
    let turned = text.replace(
        r#"<rotate y="1" angle="-30"/>"#,
        r#"<rotate y="1" angle="-27"/>"#,
    );
    assert_ne!(
        text, turned,
        "the scene's envmap rotation changed; update this test"
    );
    let loaded = tessera_scene::load_scene_str(
        &turned,
        &scenes_dir().join(SCENE),
        &[
            ("res".into(), "64".into()),
            ("rfilter".into(), "box".into()),
        ],
    )
    .expect("scene");
    let (p, what) = worst_against_mitsuba(&loaded);
    println!("sky turned by 3 degrees: worst p = {p:.3e} at {what}");
    assert!(
        p < sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3),
        "a sky turned by 3 degrees went unnoticed (p = {p:.3e})"
    );
}

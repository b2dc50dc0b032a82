//! Bump mapping renders what Mitsuba 3 renders (`scenes/bumpmap.xml`: a bump-mapped diffuse
//! sphere on a bump-mapped rough aluminium floor, one area light): the height texture's
//! gradient, the sphere's and the rectangle's partials and the tilted frame agree, on the
//! surfaces the camera sees and on those light is sampled from.
//!
//! Regions are 8x8-pixel blocks; each region's mean and its variance (pixels as strata) give a
//! z statistic for the difference from Mitsuba's image. Significance 0.01, Sidak-corrected
//! over all regions and channels. Controls that must be rejected: the same scene with both
//! heights negated (bumps become dents), and with both doubled.
use tessera::image_io::read_image;
use tessera_lab::stats::sidak_alpha;
use tessera_scene::LoadedScene;
use tessera_tests::{load_file, render_loaded, scenes_dir, worst_against_reference};

const RES: u32 = 64;
const BLOCK: u32 = 8;
const SCENE: &str = "bumpmap.xml";
const REFERENCE: &str = "refs/bumpmap_64x64_mitsuba.exr";

/// The scene at 64x64 with a box filter, its two height scales multiplied by `factor`.
fn loaded(factor: f32) -> LoadedScene {
    let sphere = format!("{}", 0.3 * factor);
    let floor = format!("{}", 0.4 * factor);
    load_file(
        SCENE,
        &[
            ("res", "64"),
            ("rfilter", "box"),
            ("sphere_scale", &sphere),
            ("floor_scale", &floor),
        ],
    )
}

fn alpha() -> f64 {
    sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3)
}

/// Worst region p-value of `l` at 512 spp against Mitsuba's image (16384 spp, made by
/// scripts/make_refs.sh); one light, so our estimator's variance stands for the reference's.
fn worst_against_mitsuba(l: &LoadedScene) -> (f64, String) {
    let ours = render_loaded(l, 512, 13);
    assert_eq!(ours.dropped(), 0);
    let reference = read_image(&scenes_dir().join(REFERENCE)).expect("reference image");
    worst_against_reference(&ours, &ours, 512, &reference, 16384.0, RES, BLOCK)
}

#[test]
fn bumpmap_matches_mitsuba() {
    let (p, what) = worst_against_mitsuba(&loaded(1.0));
    println!("bumpmap: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(p >= alpha(), "p = {p:.3e} < {:.3e} at {what}", alpha());
}

#[test]
fn negated_or_doubled_heights_are_rejected() {
    for factor in [-1.0, 2.0] {
        let (p, what) = worst_against_mitsuba(&loaded(factor));
        println!("heights times {factor}: worst p = {p:.3e} at {what}");
        assert!(
            p < alpha(),
            "heights times {factor} went unnoticed (p = {p:.3e})"
        );
    }
}

//! An area light whose radiance is a bitmap over its uv (`scenes/textured_light.xml`: a tilted
//! rectangle seen by the camera, lighting a diffuse floor) renders what Mitsuba 3 renders, and
//! our own strategies agree with each other: the texture is looked up at the right uv both
//! where a ray hits the light and where light sampling picks a point.
//!
//! Regions are 8x8-pixel blocks; each region's mean and its variance (pixels as strata) give a
//! z statistic for a difference of two renders. Significance 0.01, Sidak-corrected over all
//! regions and channels of a comparison. Control: the same scene with the texture mirrored in
//! v (`to_uv` scale y = -1) is rejected against Mitsuba's image.
use tessera::image_io::read_image;
use tessera::render::Framebuffer;
use tessera_lab::stats::sidak_alpha;
use tessera_scene::LoadedScene;
use tessera_tests::{
    load_file, region_stats, render_loaded, scenes_dir, worst_against_reference, worst_region,
};

const RES: u32 = 64;
const BLOCK: u32 = 8;
const SCENE: &str = "textured_light.xml";
const REFERENCE: &str = "refs/textured_light_64x64_mitsuba.exr";

fn loaded() -> LoadedScene {
    load_file(SCENE, &[("res", "64"), ("rfilter", "box")])
}

fn render(integrator: &str, spp: u64, seed: u64) -> Framebuffer {
    let mut l = loaded();
    l.set_integrator(Some(integrator), None)
        .expect("known integrator");
    render_loaded(&l, spp, seed)
}

fn alpha() -> f64 {
    sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3)
}

/// Worst region p-value of `l` at 512 spp against Mitsuba's image (16384 spp, made by
/// scripts/make_refs.sh); one light, so our estimator's variance stands for the reference's.
fn worst_against_mitsuba(l: &LoadedScene) -> (f64, String) {
    let ours = render_loaded(l, 512, 11);
    assert_eq!(ours.dropped(), 0);
    let reference = read_image(&scenes_dir().join(REFERENCE)).expect("reference image");
    worst_against_reference(&ours, &ours, 512, &reference, 16384.0, RES, BLOCK)
}

#[test]
fn textured_light_matches_mitsuba() {
    let (p, what) = worst_against_mitsuba(&loaded());
    println!("textured light: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(p >= alpha(), "p = {p:.3e} < {:.3e} at {what}", alpha());
}

/// Light sampling alone (path_ems) and BSDF sampling alone (path_mats) see the same light: the
/// radiance at sampled points is the one rays find there.
#[test]
fn light_sampling_and_bsdf_sampling_agree() {
    let ems = render("path_ems", 512, 2);
    let mats = render("path_mats", 2048, 3);
    let (p, what) = worst_region(&ems, RES, BLOCK, |bx, by, k| {
        region_stats(&mats, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
    });
    println!("path_ems vs path_mats: worst p = {p:.3e} at {what}");
    assert!(p >= alpha(), "p = {p:.3e} < {:.3e} at {what}", alpha());
}

#[test]
fn a_mirrored_texture_is_rejected() {
    let text = std::fs::read_to_string(scenes_dir().join(SCENE)).expect("scene file");
    let from = r#"<string name="filename" value="textures/tess_rgb.png"/>"#;
    let mirrored = text.replace(
        from,
        &format!(r#"{from}<transform name="to_uv"><scale x="1" y="-1"/></transform>"#),
    );
    assert_ne!(text, mirrored, "the scene's texture changed; update this test");
    let l = tessera_scene::load_scene_str(
        &mirrored,
        &scenes_dir().join(SCENE),
        &[
            ("res".into(), "64".into()),
            ("rfilter".into(), "box".into()),
        ],
    )
    .expect("scene");
    let (p, what) = worst_against_mitsuba(&l);
    println!("texture mirrored in v: worst p = {p:.3e} at {what}");
    assert!(p < alpha(), "a mirrored texture went unnoticed (p = {p:.3e})");
}

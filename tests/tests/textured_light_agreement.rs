//! An area light whose radiance is a bitmap over its uv (`scenes/textured_light.xml`: a tilted
//! rectangle seen by the camera, lighting a diffuse floor) renders what Mitsuba 3 renders, and
//! light sampling agrees with multiple importance sampling: the texture is looked up at the
//! right uv both where a ray hits the light and where light sampling picks a point.
//!
//! Regions are 8x8-pixel blocks; each region's mean and its variance (pixels as strata) give a
//! z statistic for a difference of two renders. Significance 0.01, Sidak-corrected over all
//! regions and channels of a comparison. Controls: the same scene with the texture mirrored in
//! v (`to_uv` scale y = -1) is rejected against Mitsuba's image, and its light-sampled render
//! against the unmirrored multiple-importance one.
use tessera::image_io::read_image;
use tessera::render::Framebuffer;
use tessera_lab::stats::sidak_alpha;
use tessera_scene::LoadedScene;
use tessera_tests::{
    load_file, load_file_edited, region_stats, render_loaded, scenes_dir, worst_against_reference,
    worst_region,
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

/// Light sampling alone (path_ems) agrees with multiple importance sampling (path_mis), where
/// BSDF sampling, which finds the texture where rays hit the light, carries much of the
/// weight: the radiance at sampled points is the one rays find there. (path_mats alone is no
/// fair partner: at the floor's far edge it reaches the light in a few grazing bounces per
/// region, too few for the regions' variance estimates.)
#[test]
fn light_sampling_and_mis_agree() {
    let ems = render("path_ems", 512, 2);
    let mis = render("path_mis", 512, 3);
    let (p, what) = worst_region(&ems, RES, BLOCK, |bx, by, k| {
        region_stats(&mis, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
    });
    println!("path_ems vs path_mis: worst p = {p:.3e} at {what}");
    assert!(p >= alpha(), "p = {p:.3e} < {:.3e} at {what}", alpha());
}

/// The scene with its light's texture mirrored in v.
fn mirrored() -> LoadedScene {
    let from = r#"<string name="filename" value="textures/tess_rgb.png"/>"#;
    let mirror = |text: &str| {
        text.replace(
            from,
            &format!(r#"{from}<transform name="to_uv"><scale x="1" y="-1"/></transform>"#),
        )
    };
    load_file_edited(SCENE, mirror, &[("res", "64"), ("rfilter", "box")])
}

#[test]
fn a_mirrored_texture_is_rejected() {
    let (p, what) = worst_against_mitsuba(&mirrored());
    println!("texture mirrored in v: worst p = {p:.3e} at {what}");
    assert!(
        p < alpha(),
        "a mirrored texture went unnoticed (p = {p:.3e})"
    );
    let mut l = mirrored();
    l.set_integrator(Some("path_ems"), None)
        .expect("known integrator");
    let ems = render_loaded(&l, 512, 2);
    let mis = render("path_mis", 512, 3);
    let (p, what) = worst_region(&ems, RES, BLOCK, |bx, by, k| {
        region_stats(&mis, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
    });
    println!("mirrored path_ems vs path_mis: worst p = {p:.3e} at {what}");
    assert!(
        p < alpha(),
        "a mirrored light-sampled texture went unnoticed (p = {p:.3e})"
    );
}

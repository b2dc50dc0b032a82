//! The `projector` (`scenes/projector.xml`: a bitmap thrown at an angle onto a diffuse plane)
//! and the textured `spot` (`scenes/spot_texture.xml`: the same plane under a spot light with a
//! bitmap in its cone) render what Mitsuba 3.9.1 renders.
//!
//! Regions are 8x8-pixel blocks; each region's mean and its variance (pixels as strata) give a
//! z statistic for the difference from Mitsuba's image (16384 spp, `scripts/make_refs.sh`).
//! Significance 0.01, Sidak-corrected over all regions and channels of a comparison. Each
//! scene has one light, so our estimator's variance stands for the reference's. Controls, each
//! rejected against the same reference: the projector's field of view 5% wider, its image
//! mirrored in u, and the spot's texture mirrored in u.
use tessera::image_io::read_image;
use tessera_lab::stats::sidak_alpha;
use tessera_scene::LoadedScene;
use tessera_tests::{render_loaded, scenes_dir, worst_against_reference};

const RES: u32 = 64;
const BLOCK: u32 = 8;

fn alpha() -> f64 {
    sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3)
}

/// `scene` (a file of `scenes/`) at 64x64 with a box filter, its text passed through `edit`
/// (which must change it, unless it is the identity) and `defines` added.
fn load(scene: &str, edit: Option<(&str, &str)>, defines: &[(&str, &str)]) -> LoadedScene {
    let path = scenes_dir().join(scene);
    let mut text = std::fs::read_to_string(&path).expect("scene file");
    if let Some((from, to)) = edit {
        let edited = text.replace(from, to);
        assert_ne!(text, edited, "{scene} changed; update this test");
        text = edited;
    }
    let mut all = vec![
        ("res".to_string(), RES.to_string()),
        ("rfilter".to_string(), "box".to_string()),
    ];
    all.extend(defines.iter().map(|(k, v)| (k.to_string(), v.to_string())));
    tessera_scene::load_scene_str(&text, &path, &all).expect("scene")
}

/// Worst region p-value of `l` at 512 spp against Mitsuba's image `reference`.
fn worst(l: &LoadedScene, reference: &str) -> (f64, String) {
    let ours = render_loaded(l, 512, 11);
    assert_eq!(ours.dropped(), 0);
    let reference = read_image(&scenes_dir().join(reference)).expect("reference image");
    worst_against_reference(&ours, &ours, 512, &reference, 16384.0, RES, BLOCK)
}

const PROJECTOR: &str = "projector.xml";
const PROJECTOR_REF: &str = "refs/projector_64x64_mitsuba.exr";
const SPOT: &str = "spot_texture.xml";
const SPOT_REF: &str = "refs/spot_texture_64x64_mitsuba.exr";
/// The bitmap element of both scenes, where a mirroring `to_uv` goes.
const BITMAP: &str = r#"<string name="filename" value="textures/tess_rgb.png"/>"#;
const MIRROR_U: &str = r#"<transform name="to_uv"><scale x="-1" y="1"/></transform>"#;

fn mirrored() -> String {
    format!("{BITMAP}{MIRROR_U}")
}

#[test]
fn projector_matches_mitsuba() {
    let (p, what) = worst(&load(PROJECTOR, None, &[]), PROJECTOR_REF);
    println!("projector: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(p >= alpha(), "p = {p:.3e} < {:.3e} at {what}", alpha());
}

#[test]
fn a_projector_fov_five_percent_wider_is_rejected() {
    let (p, what) = worst(&load(PROJECTOR, None, &[("fov", "42")]), PROJECTOR_REF);
    println!("projector fov 42 instead of 40: worst p = {p:.3e} at {what}");
    assert!(
        p < alpha(),
        "a field of view 5% off went unnoticed (p = {p:.3e})"
    );
}

#[test]
fn a_mirrored_projector_image_is_rejected() {
    let m = mirrored();
    let (p, what) = worst(&load(PROJECTOR, Some((BITMAP, &m)), &[]), PROJECTOR_REF);
    println!("projector image mirrored in u: worst p = {p:.3e} at {what}");
    assert!(p < alpha(), "a mirrored image went unnoticed (p = {p:.3e})");
}

#[test]
fn textured_spot_matches_mitsuba() {
    let (p, what) = worst(&load(SPOT, None, &[]), SPOT_REF);
    println!("textured spot: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(p >= alpha(), "p = {p:.3e} < {:.3e} at {what}", alpha());
}

#[test]
fn a_mirrored_spot_texture_is_rejected() {
    let m = mirrored();
    let (p, what) = worst(&load(SPOT, Some((BITMAP, &m)), &[]), SPOT_REF);
    println!("spot texture mirrored in u: worst p = {p:.3e} at {what}");
    assert!(
        p < alpha(),
        "a mirrored texture went unnoticed (p = {p:.3e})"
    );
}

//! `volpathmis` agrees with Mitsuba 3.9.1's `volpathmis` region by region on
//! `scenes/media/chromatic_fog.xml` (a smoke cube whose extinction differs twelvefold between
//! the red and blue channels, a blend of hg and Rayleigh scattering, a fog with a tabulated phase
//! function), against the reference made by `scripts/make_refs.sh` (64x64, 8192 spp, box
//! filter; ours at 2048 spp); a render whose smoke extinction is 5% high must be rejected. On the same scene
//! `volpath` and `volpathmis` agree with each other (their weights differ, not their
//! expectation), with a control 2% off; and `volpathmis` on the heterogeneous `smoke.xml`
//! (where it falls back to volpath's weights on segments through the grid) agrees with
//! Mitsuba's reference of that scene.
//!
//! Regions are 8x8-pixel blocks, each compared by a z statistic; significance 0.01,
//! Sidak-corrected over the regions and channels of a comparison.
use tessera::image_io::read_image;
use tessera::render::Framebuffer;
use tessera_lab::stats::sidak_alpha;
use tessera_tests::{
    load_file, region_stats, render_loaded, scenes_dir, worst_against_reference, worst_region,
};

const BLOCK: u32 = 8;
const REF_SPP: f64 = 8192.0;

fn render(
    name: &str,
    res: u32,
    spp: u64,
    integrator: &str,
    defines: &[(&str, &str)],
) -> Framebuffer {
    let res = res.to_string();
    let mut all = vec![("res", res.as_str()), ("rfilter", "box")];
    all.extend_from_slice(defines);
    let mut loaded = load_file(&format!("media/{name}.xml"), &all);
    loaded
        .set_integrator(Some(integrator), None)
        .expect("known integrator");
    let fb = render_loaded(&loaded, spp, 41);
    assert_eq!(fb.dropped(), 0, "non-finite samples");
    fb
}

/// Our `volpathmis` render of `name` against Mitsuba's reference `reference`, and the control.
fn agrees(name: &str, res: u32, spp: u64, reference: &str, control: &[(&str, &str)]) {
    let reference = read_image(&scenes_dir().join("refs").join(reference)).expect("reference");
    let alpha = sidak_alpha(0.01, (res / BLOCK).pow(2) as usize * 3);
    let ours = render(name, res, spp, "volpathmis", &[]);
    let (p, what) = worst_against_reference(&ours, &ours, spp, &reference, REF_SPP, res, BLOCK);
    eprintln!("{name}: volpathmis vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(p >= alpha, "{name}: p = {p:.3e} < {alpha:.3e} at {what}");
    let wrong = render(name, res, spp, "volpathmis", control);
    let (p, what) = worst_against_reference(&wrong, &wrong, spp, &reference, REF_SPP, res, BLOCK);
    eprintln!("{name}, control {control:?}: worst p = {p:.3e} at {what}");
    assert!(p < alpha, "{name}: the control passed (p = {p:.3e})");
}

#[test]
fn chromatic_fog_matches_mitsuba_volpathmis() {
    agrees(
        "chromatic_fog",
        64,
        2048,
        "chromatic_fog_64x64_mitsuba.exr",
        &[("smoke_scale", "6.3")],
    );
}

#[test]
fn heterogeneous_smoke_matches_mitsuba() {
    agrees(
        "smoke",
        32,
        384,
        "smoke_32x32_mitsuba.exr",
        &[("smoke_scale", "6.3")],
    );
}

#[test]
fn volpath_and_volpathmis_agree() {
    let res = 64;
    let a = render("chromatic_fog", res, 1024, "volpathmis", &[]);
    let mut l = load_file(
        "media/chromatic_fog.xml",
        &[("res", "64"), ("rfilter", "box")],
    );
    l.set_integrator(Some("volpath"), None).expect("volpath");
    let b = render_loaded(&l, 1024, 42);
    let alpha = sidak_alpha(0.01, (res / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst_region(&a, res, BLOCK, |bx, by, k| {
        region_stats(&b, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
    });
    eprintln!("volpathmis vs volpath on chromatic_fog: worst p = {p:.3e} at {what}");
    assert!(p >= alpha, "p = {p:.3e} < {alpha:.3e} at {what}");
    let (p, _) = worst_region(&a, res, BLOCK, |bx, by, k| {
        let (m, v) = region_stats(&b, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k];
        (m * 1.02, v)
    });
    eprintln!("control, volpath 2% brighter: worst p = {p:.3e}");
    assert!(p < alpha, "the control passed (p = {p:.3e})");
}

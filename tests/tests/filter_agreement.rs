//! A filter with negative lobes gives Mitsuba 3's image: the Cornell box with the `lanczos`
//! filter (3 lobes), rendered by Tessera (filter importance sampling, signed weights) and by
//! Mitsuba 3.9.1 (splatting with the filter, `scenes/refs/cbox_64x64_lanczos_mitsuba.exr`, made
//! by `scripts/make_refs.sh`), agrees block by block.
//!
//! Blocks are 2x2 pixels, small enough that the filter's shape shows at edges (the light, the
//! walls' corners: a Lanczos filter rings there). The reference's own variance is estimated from
//! Tessera's render, scaled by the ratio of sample counts (Mitsuba's splatting estimator has a
//! different variance, but at 16 times our samples its share is small either way). Significance
//! 0.01, Šidák-corrected over blocks and channels. Controls: Tessera's renders with the
//! Gaussian and the Mitchell filters must be rejected against the same reference, so the test
//! tells filters apart.
use tessera::image_io::read_image;
use tessera_lab::stats::sidak_alpha;
use tessera_tests::{load_file, render_loaded, scenes_dir, worst_against_reference};

const RES: u32 = 64;
const BLOCK: u32 = 2;
const SPP: u64 = 512;
const REF_SPP: f64 = 8192.0;

/// The worst block's p-value of Tessera's cbox with filter `rfilter` against the reference.
fn worst_p(rfilter: &str, seed: u64) -> (f64, String) {
    let mut loaded = load_file("cbox.xml", &[("res", "64"), ("rfilter", rfilter)]);
    loaded
        .set_integrator(Some("path_mis"), None)
        .expect("known integrator");
    let ours = render_loaded(&loaded, SPP, seed);
    let reference = read_image(&scenes_dir().join("refs/cbox_64x64_lanczos_mitsuba.exr"))
        .expect("reference image");
    worst_against_reference(&ours, &ours, SPP, &reference, REF_SPP, RES, BLOCK)
}

fn alpha() -> f64 {
    sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3)
}

#[test]
fn lanczos_matches_mitsuba() {
    let (p, what) = worst_p("lanczos", 31);
    eprintln!("lanczos: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(
        p >= alpha(),
        "lanczos: p = {p:.3e} < {:.3e} at {what}",
        alpha()
    );
}

#[test]
fn other_filters_are_told_apart() {
    for rfilter in ["gaussian", "mitchell"] {
        let (p, what) = worst_p(rfilter, 32);
        eprintln!("{rfilter} against the lanczos reference: worst p = {p:.3e} at {what}");
        assert!(p < alpha(), "{rfilter} passed as lanczos (p = {p:.3e})");
    }
}

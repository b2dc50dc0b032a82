//! `volpath` agrees with Mitsuba 3.9.1's `volpath` region by region on a heterogeneous medium:
//! `scenes/media/smoke.xml`, a plume from a 12x16x12 density grid (`scenes/media/smoke.vol`,
//! made by `scripts/make_smoke_grid.py`) with a chromatic albedo and a Henyey-Greenstein phase
//! function, bounded by a null cube, lit by a rectangle light and a dim sky; against the reference
//! made by `scripts/make_refs.sh` (32x32, 8192 spp, box filter). The same comparison of a render
//! whose extinction is 5% high must be rejected. (mitsuba-data's heterogeneous test scenes are
//! compared in `real_agreement.rs`.)
//!
//! Regions are 8x8-pixel blocks, each compared by a z statistic (the reference's variance
//! estimated from our render, scaled by the sample counts); significance 0.01, Sidak-corrected
//! over the regions and channels.
use tessera::image_io::read_image;
use tessera_lab::stats::sidak_alpha;
use tessera_tests::{load_file, render_loaded, scenes_dir, worst_against_reference};

const RES: u32 = 32;
const BLOCK: u32 = 8;
const SPP: u64 = 384;
const REF_SPP: f64 = 8192.0;

fn worst_against_mitsuba(defines: &[(&str, &str)]) -> (f64, String) {
    let mut all = vec![("res", "32"), ("rfilter", "box")];
    all.extend_from_slice(defines);
    let loaded = load_file("media/smoke.xml", &all);
    let ours = render_loaded(&loaded, SPP, 31);
    assert_eq!(ours.dropped(), 0, "non-finite samples");
    let reference =
        read_image(&scenes_dir().join("refs/smoke_32x32_mitsuba.exr")).expect("reference image");
    worst_against_reference(&ours, &ours, SPP, &reference, REF_SPP, RES, BLOCK)
}

#[test]
fn smoke_matches_mitsuba() {
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst_against_mitsuba(&[]);
    eprintln!("smoke: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(p >= alpha, "smoke: p = {p:.3e} < {alpha:.3e} at {what}");
    let (p, what) = worst_against_mitsuba(&[("smoke_scale", "6.3")]);
    eprintln!("smoke, control (extinction 5% high): worst p = {p:.3e} at {what}");
    assert!(p < alpha, "smoke: the control passed (p = {p:.3e})");
}

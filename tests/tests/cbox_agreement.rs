//! The Cornell box, rendered by each integrator and by Mitsuba 3, agrees region by region.
//!
//! Regions are 8x8-pixel blocks; each region's mean and its variance (pixels as strata, from the
//! per-pixel sums of squares) give a z statistic for a difference of two renders. Significance
//! 0.01, Sidak-corrected over all regions, channels and pairs of a test.
use tessera::image_io::read_image;
use tessera::render::Framebuffer;
use tessera_lab::stats::sidak_alpha;
use tessera_tests::{
    load_file, region_stats, render_like_mitsuba, render_loaded, scenes_dir,
    worst_against_reference, worst_region,
};

const RES: u32 = 64;
const BLOCK: u32 = 8;

fn render_with(strategy: &str, spp: u64, seed: u64) -> Framebuffer {
    render_scene("cbox.xml", strategy, spp, seed)
}

fn render_scene(file: &str, strategy: &str, spp: u64, seed: u64) -> Framebuffer {
    let mut loaded = load_file(file, &[("res", "64"), ("rfilter", "box")]);
    loaded
        .set_integrator(Some(strategy), None)
        .expect("known integrator");
    render_loaded(&loaded, spp, seed)
}

/// path_mats, path_half, path_mis and path_ems converge to the same image.
#[test]
fn integrators_agree_on_the_cornell_box() {
    let spp = 512;
    let renders = [
        ("path_mats", render_with("path_mats", spp, 1)),
        ("path_half", render_with("path_half", spp, 2)),
        ("path_mis", render_with("path_mis", spp, 3)),
        ("path_ems", render_with("path_ems", spp, 4)),
    ];
    let n_tests = 6 * (RES / BLOCK).pow(2) as usize * 3;
    let alpha = sidak_alpha(0.01, n_tests);
    for i in 0..renders.len() {
        for j in i + 1..renders.len() {
            let (na, a) = (&renders[i].0, &renders[i].1);
            let (nb, b) = (&renders[j].0, &renders[j].1);
            assert_eq!(a.dropped() + b.dropped(), 0);
            let (p, what) = worst_region(a, RES, BLOCK, |bx, by, k| {
                region_stats(b, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
            });
            eprintln!("{na} vs {nb}: worst p = {p:.3e} at {what}");
            assert!(
                p >= alpha,
                "{na} vs {nb}: p = {p:.3e} < {alpha:.3e} at {what}"
            );
        }
    }
}

/// Our render of a scene file agrees with Mitsuba 3's (`scenes/refs/NAME_64x64_mitsuba.exr`,
/// 16384 spp, made by scripts/make_refs.sh).
fn matches_mitsuba(name: &str) {
    let spp = 512;
    let ref_spp = 16384.0;
    let mut loaded = load_file(&format!("{name}.xml"), &[("res", "64"), ("rfilter", "box")]);
    loaded
        .set_integrator(Some("path_mis"), None)
        .expect("known integrator");
    let ours = render_loaded(&loaded, spp, 11);
    let like = render_like_mitsuba(&loaded, spp, 12);
    let reference = read_image(&scenes_dir().join(format!("refs/{name}_64x64_mitsuba.exr")))
        .expect("reference image");
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst_against_reference(&ours, &like, spp, &reference, ref_spp, RES, BLOCK);
    eprintln!("{name}: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(
        p >= alpha,
        "{name}: Tessera vs Mitsuba 3: p = {p:.3e} < {alpha:.3e} at {what}"
    );
}

#[test]
fn cornell_box_matches_mitsuba() {
    matches_mitsuba("cbox");
}

#[test]
fn cs500_spheres_match_mitsuba() {
    matches_mitsuba("cs500_spheres");
}

/// The comparison has power: a reference 2% too bright is rejected.
#[test]
fn comparison_rejects_a_two_percent_bias() {
    let ours = render_with("path_mis", 512, 11);
    let (p, _) = worst_region(&ours, RES, BLOCK, |bx, by, k| {
        let (m, v) = region_stats(&ours, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k];
        (m * 1.02, v * 512.0 / 16384.0)
    });
    assert!(
        p < sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3),
        "a 2% bias went unnoticed (p = {p:.3e})"
    );
}

/// Choosing lights by power or uniformly changes the noise, never the image: the CS500 scene
/// (three sphere lights of different power and an environment) agrees region by region. (The
/// default, by contribution at each vertex, is held against both in tests/light_select.rs.)
#[test]
fn light_selection_by_power_or_uniform_agrees() {
    use tessera_core::light::LightSelection;
    let mut loaded = load_file("cs500_spheres.xml", &[("res", "64"), ("rfilter", "box")]);
    loaded.scene.set_light_selection(LightSelection::Power);
    let power = render_loaded(&loaded, 256, 21);
    loaded.scene.set_light_selection(LightSelection::Uniform);
    let uniform = render_loaded(&loaded, 256, 22);
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst_region(&power, RES, BLOCK, |bx, by, k| {
        region_stats(&uniform, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
    });
    eprintln!("power vs uniform light selection: worst p = {p:.3e} at {what}");
    assert!(
        p >= alpha,
        "power vs uniform light selection: p = {p:.3e} < {alpha:.3e} at {what}"
    );
}

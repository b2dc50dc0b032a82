//! `volpath` agrees with Mitsuba 3.9.1's `volpath` region by region on scenes with media
//! (`scenes/media/fog_cbox.xml`: a medium on the sensor and a null-bounded cube of chromatic,
//! forward-scattering smoke; `scenes/media/glass_sphere.xml`: a dielectric sphere holding an
//! absorbing and scattering medium; `scenes/media/albedo_grid.xml`: a homogeneous medium whose
//! albedo is a tiled voxel grid; `scenes/media/flakes.xml`: microflake media, the `sggx`
//! phase function with its matrix from a 6-channel grid in a heterogeneous box and from one
//! voxel in a homogeneous sphere, rendered absorbing only, as Mitsuba's sggx sampling is off
//! its own density: the extinction's dependence on place and direction is what is compared),
//! against references made by `scripts/make_refs.sh` (64x64,
//! 8192 spp, box filter). The same comparison of renders whose extinction is 5% high must be
//! rejected. And on a scene without media, `volpath` renders what `path` renders: the same
//! bits, and its own loop the same image in expectation.
//!
//! Regions are 8x8-pixel blocks, each compared by a z statistic (the reference's variance
//! estimated from our render, scaled by the sample counts); significance 0.01,
//! Sidak-corrected over the regions and channels of a comparison.
use tessera::image_io::read_image;
use tessera_lab::stats::sidak_alpha;
use tessera_tests::{
    load_file, load_file_edited, region_stats, render_loaded, scenes_dir, worst_against_reference,
    worst_region,
};

const RES: u32 = 64;
const BLOCK: u32 = 8;
const SPP: u64 = 1024;
const REF_SPP: f64 = 8192.0;

/// The worst p-value of our render of `scenes/media/NAME.xml` (with `defines`) against
/// Mitsuba's reference.
fn worst_against_mitsuba(name: &str, defines: &[(&str, &str)]) -> (f64, String) {
    let mut all = vec![("res", "64"), ("rfilter", "box")];
    all.extend_from_slice(defines);
    let loaded = load_file(&format!("media/{name}.xml"), &all);
    let ours = render_loaded(&loaded, SPP, 21);
    assert_eq!(ours.dropped(), 0, "non-finite samples");
    let reference = read_image(&scenes_dir().join(format!("refs/{name}_64x64_mitsuba.exr")))
        .expect("reference image");
    worst_against_reference(&ours, &ours, SPP, &reference, REF_SPP, RES, BLOCK)
}

fn agrees(name: &str, control: &[(&str, &str)]) {
    agrees_with(name, &[], control)
}

/// [`agrees`] for the scene with `defines`.
fn agrees_with(name: &str, defines: &[(&str, &str)], control: &[(&str, &str)]) {
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst_against_mitsuba(name, defines);
    eprintln!("{name}: Tessera vs Mitsuba 3: worst p = {p:.3e} at {what}");
    assert!(p >= alpha, "{name}: p = {p:.3e} < {alpha:.3e} at {what}");
    let control_defines = [defines, control].concat();
    let (p, what) = worst_against_mitsuba(name, &control_defines);
    eprintln!("{name}, control {control:?}: worst p = {p:.3e} at {what}");
    assert!(
        p < alpha,
        "{name}: the control {control:?} passed (p = {p:.3e})"
    );
}

#[test]
fn fog_cornell_box_matches_mitsuba() {
    agrees("fog_cbox", &[("fog_scale", "1.05"), ("smoke_scale", "4.2")]);
}

#[test]
fn glass_sphere_with_medium_matches_mitsuba() {
    agrees("glass_sphere", &[("sigma_scale", "2.52")]);
}

#[test]
fn homogeneous_medium_with_a_grid_albedo_matches_mitsuba() {
    agrees("albedo_grid", &[("ext_scale", "5.25")]);
}

#[test]
fn microflake_media_match_mitsuba() {
    let absorbing = [("fibre_albedo", "0"), ("sheet_albedo", "0")];
    agrees_with("flakes", &absorbing, &[("flake_scale", "1.05")]);
}

/// On a scene of surfaces alone `volpath` is `path`: the same bits from the same seed (its
/// medium bookkeeping would never trigger, so it is not run). Control: another seed differs.
#[test]
fn volpath_is_path_without_media() {
    let render = |name: &str, seed: u64| {
        let mut l = load_file("cbox.xml", &[("res", "32"), ("rfilter", "box")]);
        l.set_integrator(Some(name), None)
            .expect("known integrator");
        render_loaded(&l, 16, seed)
    };
    let path = render("path", 5);
    assert_eq!(render("volpath", 5), path);
    assert_ne!(render("volpath", 6), path);
}

/// `volpath`'s own loop on the Cornell box (run because of a `null` sphere out of the way,
/// which it steps through) converges to what `path` renders. Their estimators differ in
/// their use of the sampler and in Russian roulette's timing, so the bits differ.
#[test]
fn volpath_loop_renders_what_path_renders_on_surfaces() {
    let null_sphere = |text: &str| {
        text.replace(
            "</scene>",
            r#"<shape type="sphere"><point name="center" x="0" y="-30" z="0"/>
               <float name="radius" value="0.5"/><bsdf type="null"/></shape></scene>"#,
        )
    };
    let defines = [("res", "64"), ("rfilter", "box")];
    let mut v = load_file_edited("cbox.xml", null_sphere, &defines);
    v.set_integrator(Some("volpath"), None).expect("volpath");
    let a = render_loaded(&v, 512, 1);
    let mut l = load_file("cbox.xml", &defines);
    l.set_integrator(Some("path"), None).expect("path");
    let b = render_loaded(&l, 512, 2);
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst_region(&a, RES, BLOCK, |bx, by, k| {
        region_stats(&b, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
    });
    eprintln!("volpath vs path on the Cornell box: worst p = {p:.3e} at {what}");
    assert!(p >= alpha, "p = {p:.3e} < {alpha:.3e} at {what}");
    // Control: the same comparison against path rendered 2% brighter must fail.
    let (p, _) = worst_region(&a, RES, BLOCK, |bx, by, k| {
        let (m, v) = region_stats(&b, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k];
        (m * 1.02, v)
    });
    assert!(p < alpha, "control (path 2% brighter) passed: p = {p:.3e}");
}

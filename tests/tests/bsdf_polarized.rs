//! `pplastic` and `polarizer` (Mitsuba 3's polarization plugins as its RGB variants render
//! them): sampling against the pdf, the sampled weights against the integrated `eval`, the
//! polarizer's pass-through, the back side, parameter errors and the warning for what only
//! polarized light would see. (Agreement of eval and pdf with Mitsuba 3 itself is
//! `bsdf_mitsuba_eval.rs`, on the `pplastic*` and `polarizer` tables of `tests/bsdf_cases/`.)
//!
//! The chi-square tests (listed in [`N_CHI2`]) run at the Šidák-corrected level of 0.01 over
//! the file; test `k` uses seed `k`. Run with `--nocapture` to see every p-value.

use std::path::Path;

use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_lab::stats::{sampled_albedo, sidak_alpha, BsdfChi2, Pcg32, SphereChi2};
use tessera_tests::bsdf::{assert_cases_rejected_on_their_line, dir_at, load_bsdf_xml};

/// Chi-square tests in this file: 10 `pplastic` cases, and the control's passing half.
const N_CHI2: usize = 11;

const UV: Vec2 = Vec2::new(0.25, 0.75);

fn alpha() -> f64 {
    sidak_alpha(0.01, N_CHI2)
}

fn dir(deg: f32) -> Vec3 {
    dir_at(deg, 0.7)
}

fn pplastic(body: &str) -> String {
    format!(r#"<bsdf type="pplastic">{body}</bsdf>"#)
}

fn roughness_png() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bsdf_cases/textures/roughness.png")
        .display()
        .to_string()
}

#[test]
fn pplastic_samples_its_pdf() {
    let ggx_aniso = pplastic(
        r#"<string name="distribution" value="ggx"/><float name="alpha_u" value="0.08"/>
        <float name="alpha_v" value="0.45"/><float name="eta" value="1.33"/>
        <rgb name="diffuse_reflectance" value="0.05, 0.03, 0.1"/>"#,
    );
    let all_normals = |dist: &str, a: f32| {
        pplastic(&format!(
            r#"<string name="distribution" value="{dist}"/><float name="alpha" value="{a}"/>
            <boolean name="sample_visible" value="false"/>
            <rgb name="diffuse_reflectance" value="0.6, 0.3, 0.1"/>"#
        ))
    };
    let inverted = pplastic(
        r#"<float name="int_ior" value="1.0"/><float name="ext_ior" value="1.5"/>
        <float name="alpha" value="0.2"/>"#,
    );
    let textured = pplastic(&format!(
        r#"<texture type="checkerboard" name="diffuse_reflectance">
        <rgb name="color0" value="0.8, 0.1, 0.3"/><rgb name="color1" value="0.05, 0.5, 0.9"/>
        </texture><texture name="alpha" type="bitmap"><string name="filename" value="{}"/>
        </texture>"#,
        roughness_png()
    ));
    let default = pplastic("");
    // (label, material, incidence in degrees): test k uses seed k + 1.
    #[rustfmt::skip]
    let cases = [
        ("default", default.as_str(), 0.0),
        ("default", default.as_str(), 45.0),
        ("default", default.as_str(), 85.0),
        ("ggx anisotropic, eta 1.33, dark", ggx_aniso.as_str(), 30.0),
        ("ggx anisotropic, eta 1.33, dark", ggx_aniso.as_str(), 80.0),
        ("beckmann 0.05 all normals", &all_normals("beckmann", 0.05), 60.0),
        ("ggx 0.7 all normals", &all_normals("ggx", 0.7), 20.0),
        // Beyond the critical angle (41.8 deg) the diffuse term is zero: only glossy samples
        // carry weight, but the diffuse lobe is still drawn and is part of the pdf.
        ("eta 0.67", inverted.as_str(), 20.0),
        ("eta 0.67", inverted.as_str(), 60.0),
        ("textured albedo and roughness", textured.as_str(), 50.0),
    ];
    let a = alpha();
    let mut failed = Vec::new();
    for (k, &(name, xml, deg)) in cases.iter().enumerate() {
        let b = load_bsdf_xml(xml);
        let r = BsdfChi2 {
            samples: 500_000,
            ..BsdfChi2::default()
        }
        .run(&b, dir(deg), UV, k as u64 + 1);
        println!("{name} at {deg} deg: {r}");
        if !r.passes(a) {
            failed.push(format!("{name} at {deg} deg: {r}"));
        }
    }
    assert!(failed.is_empty(), "alpha = {a:.3e}:\n{}", failed.join("\n"));
}

/// Control: the harness rejects a pplastic whose claimed specular probability is wrong
/// (samples of the default, specular weight 1 / 1.5 = 0.667, judged against the pdf of one
/// with diffuse reflectance 0.2, weight 1 / 1.2 = 0.833), and accepts the right pdf.
#[test]
fn a_wrong_lobe_probability_is_rejected() {
    let drawn = load_bsdf_xml(&pplastic(""));
    let claimed = load_bsdf_xml(&pplastic(
        r#"<float name="diffuse_reflectance" value="0.2"/>"#,
    ));
    let wi = dir(35.0);
    let run = |pdf_of: &Bsdf| {
        let mut rng = Pcg32::new(99);
        SphereChi2 {
            theta_bins: 20,
            phi_bins: 40,
            samples: 500_000,
        }
        .run(
            |u| Some(drawn.sample(wi, rng.next_f32(), u, UV)?.wo),
            |w| f64::from(pdf_of.pdf(wi, w, UV)),
            7,
        )
    };
    let r = run(&claimed);
    println!("control: {r}");
    assert!(!r.passes(alpha()), "{r}");
    let r = run(&drawn);
    println!("right pdf: {r}");
    assert!(r.passes(alpha()), "{r}");
}

/// `integral eval(wi, wo) dwo` over the upper hemisphere by a midpoint rule in
/// `(cos theta, phi)`, fine enough near the glossy peak for the roughnesses used here.
fn integrated_albedo(b: &Bsdf, wi: Vec3) -> Vec3 {
    let (nz, np) = (2000, 400);
    let mut s = glam::DVec3::ZERO;
    for i in 0..nz {
        let z = (i as f64 + 0.5) / nz as f64;
        let r = (1.0 - z * z).sqrt();
        for j in 0..np {
            let p = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
            let wo = glam::DVec3::new(r * p.cos(), r * p.sin(), z).as_vec3();
            s += b.eval(wi, wo, UV).as_dvec3();
        }
    }
    (s * std::f64::consts::TAU / (nz * np) as f64).as_vec3()
}

/// The sampled weights `eval / pdf` average to the integral of `eval` (a t-test per channel:
/// within 4 standard errors plus the quadrature's 0.2%), for a glossy and a rough material;
/// control: the weights of one material against the integral of another (eta 1.49 vs 1.6).
#[test]
fn pplastic_weights_integrate_eval() {
    let glossy = load_bsdf_xml(&pplastic(
        r#"<rgb name="diffuse_reflectance" value="0.2, 0.5, 0.8"/><float name="alpha" value="0.15"/>"#,
    ));
    let rough = load_bsdf_xml(&pplastic(
        r#"<string name="distribution" value="ggx"/><float name="alpha" value="0.6"/>
        <rgb name="specular_reflectance" value="0.7, 0.8, 0.9"/>"#,
    ));
    let other = load_bsdf_xml(&pplastic(
        r#"<rgb name="diffuse_reflectance" value="0.2, 0.5, 0.8"/><float name="alpha" value="0.15"/>
        <float name="int_ior" value="1.6"/>"#,
    ));
    let agree = |sampled: &Bsdf, integrated: &Bsdf, deg: f32, seed: u64| {
        let wi = dir(deg);
        let (mean, se) = sampled_albedo(sampled, wi, UV, 400_000, seed);
        let exact = integrated_albedo(integrated, wi);
        println!("{deg} deg: sampled {mean} +- {se}, integrated {exact}");
        (0..3).all(|c| (mean[c] - exact[c]).abs() <= 4.0 * se[c] + 2e-3 * exact[c])
    };
    assert!(agree(&glossy, &glossy, 30.0, 1));
    assert!(agree(&glossy, &glossy, 75.0, 2));
    assert!(agree(&rough, &rough, 50.0, 3));
    assert!(!agree(&glossy, &other, 30.0, 1), "control not caught");
}

#[test]
fn pplastic_back_side_is_black() {
    let b = load_bsdf_xml(&pplastic(""));
    let (up, down) = (dir(30.0), -dir(50.0));
    assert_eq!(b.eval(down, up, UV), Vec3::ZERO);
    assert_eq!(b.eval(up, down, UV), Vec3::ZERO);
    assert_eq!(b.pdf(down, up, UV), 0.0);
    assert!(b.sample(down, 0.3, Vec2::new(0.4, 0.6), UV).is_none());
    // Control: the front side reflects.
    assert!(b.eval(up, dir(40.0), UV).min_element() > 0.0);
}

/// The polarizer passes every direction straight through, from either side, weighted half the
/// transmittance, as a delta component of probability 1; it has no smooth part.
#[test]
fn polarizer_passes_half_the_light_straight_through() {
    let b = load_bsdf_xml(
        r#"<bsdf type="polarizer"><rgb name="transmittance" value="0.9, 0.7, 0.4"/>
        <float name="theta" value="-30"/></bsdf>"#,
    );
    assert!(!b.has_smooth() && b.has_delta());
    let mut rng = Pcg32::new(5);
    for k in 0..1000 {
        let wi = tessera_tests::bsdf::uniform_direction(rng.next_vec2(), true);
        let s = b
            .sample(wi, rng.next_f32(), rng.next_vec2(), UV)
            .unwrap_or_else(|| panic!("no sample at {wi}"));
        assert_eq!(s.wo, -wi, "sample {k}");
        assert_eq!(s.weight, Vec3::new(0.45, 0.35, 0.2), "sample {k}");
        assert!(s.delta && s.pdf == 1.0 && s.eta == 1.0, "sample {k}");
        assert_eq!(b.eval(wi, -wi, UV), Vec3::ZERO);
        assert_eq!(b.pdf(wi, -wi, UV), 0.0);
    }
    // The default passes half.
    let d = load_bsdf_xml(r#"<bsdf type="polarizer"/>"#);
    let s = d.sample(dir(20.0), 0.5, Vec2::splat(0.5), UV).unwrap();
    assert_eq!(s.weight, Vec3::splat(0.5));
}

#[test]
fn bad_parameters_are_located_errors() {
    #[rustfmt::skip]
    let cases = [
        ("pplastic", r#"<float name="eta" value="1.3"/><float name="int_ior" value="1.5"/>"#, "not both"),
        ("pplastic", r#"<float name="eta" value="1.3"/><float name="ext_ior" value="1.2"/>"#, "not both"),
        ("pplastic", r#"<float name="eta" value="-1.3"/>"#, "eta"),
        ("pplastic", r#"<float name="int_ior" value="1.000277"/>"#, "differ"),
        ("pplastic", r#"<string name="int_ior" value="unobtainium"/>"#, "unknown material"),
        ("pplastic", r#"<float name="alpha" value="0"/>"#, "alpha"),
        ("pplastic", r#"<float name="alpha_u" value="0.1"/>"#, "alpha_v"),
        ("pplastic", r#"<string name="distribution" value="phong"/>"#, "distribution"),
        ("pplastic", r#"<float name="diffuse_reflectance" value="1.2"/>"#, "diffuse_reflectance"),
        ("pplastic", r#"<float name="nonlinear" value="1"/>"#, "nonlinear"),
        ("polarizer", r#"<float name="transmittance" value="-0.5"/>"#, "transmittance"),
        ("polarizer", r#"<string name="polarizing" value="maybe"/>"#, "polarizing"),
        ("polarizer", r#"<string name="theta" value="north"/>"#, "theta"),
    ];
    assert_cases_rejected_on_their_line(&cases, false);
}

fn warnings(bsdf: &str) -> Vec<String> {
    let text = format!(
        "<scene version=\"3.0.0\">\n{bsdf}\n<shape type=\"rectangle\"><ref id=\"b\"/></shape>\n\
         <sensor type=\"perspective\"/>\n</scene>\n"
    );
    tessera_scene::load_scene_str(&text, Path::new("/nowhere/p.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"))
        .warnings
}

/// The polarizer's angle and switch change nothing without polarization: a located warning
/// each. Control: a polarizer without them warns of nothing.
#[test]
fn polarization_only_parameters_are_warned() {
    let w = warnings(
        r#"<bsdf type="polarizer" id="b"><float name="theta" value="45"/><boolean name="polarizing" value="false"/></bsdf>"#,
    );
    println!("{w:?}");
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].starts_with("/nowhere/p.xml:2:"), "{w:?}");
    assert!(
        w[0].contains("\"theta\"") && w[1].contains("\"polarizing\""),
        "{w:?}"
    );
    let w = warnings(r#"<bsdf type="polarizer" id="b"/>"#);
    assert!(w.is_empty(), "{w:?}");
}

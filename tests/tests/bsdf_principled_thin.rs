//! `principledthin` (Mitsuba 3): sampling against the pdf from both sides (with the
//! per-sample check that the weight is `eval / pdf`), finite non-negative values at extreme
//! parameters and grazing angles, the mean sample weight against the quadrature of `eval`, the
//! symmetry of the sheet, and parameter errors. (Agreement of eval and pdf with Mitsuba 3
//! itself is `bsdf_mitsuba_eval.rs`, on the `principledthin_*` tables of `tests/bsdf_cases/`.)
//!
//! The chi-square tests (listed in [`N_CHI2`]) run at the Šidák-corrected level of 0.01 over
//! the file; test `k` uses seed `k`. Run with `--nocapture` to see every p-value.

use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_lab::stats::Pcg32;
use tessera_tests::bsdf::{
    assert_cases_rejected_on_their_line, dir_at, load_bsdf_xml, uniform_direction,
};
use tessera_tests::bsdf_checks::{
    assert_chi2_cases, assert_finite_and_consistent, assert_smooth_two_input_traits,
    assert_wrong_density_rejected, texture_count, AlbedoAgreement,
};

/// Chi-square tests in this file: the cases of `samples_its_pdf`.
const N_CHI2: usize = 10;

const UV: Vec2 = Vec2::new(0.25, 0.75);

fn thin(props: &str) -> Bsdf {
    load_bsdf_xml(&format!(r#"<bsdf type="principledthin">{props}</bsdf>"#))
}

/// A unit direction at polar angle `deg` (above 90: from the back) and azimuth 0.7 rad.
fn dir(deg: f32) -> Vec3 {
    dir_at(deg, 0.7)
}

const LEAF: &str = r#"<rgb name="base_color" value="0.2, 0.6, 0.1"/>
    <float name="roughness" value="0.5"/><float name="diff_trans" value="0.8"/>
    <float name="sheen" value="0.3"/><float name="flatness" value="0.5"/>"#;
const GLASS: &str = r#"<rgb name="base_color" value="0.7, 0.1, 0.1"/>
    <float name="roughness" value="0.15"/><float name="spec_tint" value="0.1"/>
    <float name="anisotropic" value="0.5"/><float name="spec_trans" value="0.8"/>
    <float name="diff_trans" value="0.3"/><float name="eta" value="1.33"/>"#;
const MIXED: &str = r#"<rgb name="base_color" value="0.5, 0.4, 0.9"/>
    <float name="roughness" value="0.6"/><float name="spec_trans" value="0.4"/>
    <float name="eta" value="1.6"/><float name="spec_tint" value="0.7"/>
    <float name="sheen" value="0.5"/><float name="diff_trans" value="1.5"/>
    <float name="specular_reflectance_sampling_rate" value="2"/>
    <float name="diffuse_transmittance_sampling_rate" value="0.5"/>"#;

/// Every lobe's sampling against the mixture density, from both sides; `BsdfChi2` also checks
/// every sample's `pdf` against `pdf()` and `weight * pdf` against `eval()`.
#[test]
fn samples_its_pdf() {
    #[rustfmt::skip]
    let cases: [(&str, &str, f32); N_CHI2] = [
        ("default", "", 30.0),
        ("default, from the back", "", 160.0),
        ("leaf", LEAF, 0.0),
        ("leaf, from the back", LEAF, 120.0),
        ("glass", GLASS, 20.0),
        ("glass", GLASS, 80.0),
        ("glass, from the back", GLASS, 135.0),
        ("mixed", MIXED, 50.0),
        ("mixed, from the back", MIXED, 175.0),
        ("rough glass, eta 0.5", r#"<float name="spec_trans" value="1"/>
            <float name="roughness" value="0.9"/><float name="eta" value="0.5"/>"#, 60.0),
    ];
    let cases =
        cases.map(|(name, props, deg)| (format!("{name} at {deg} deg"), thin(props), dir(deg)));
    assert_chi2_cases(cases, UV, 0, N_CHI2);
}

/// Control: directions sampled with specular transmission rate 1, judged against the density
/// of rate 1.5, are rejected; against their own density they pass.
#[test]
fn a_wrong_lobe_probability_is_rejected() {
    let drawn = thin(GLASS);
    let claimed = thin(&format!(
        r#"{GLASS}<float name="specular_transmittance_sampling_rate" value="1.5"/>"#
    ));
    let wi = dir(20.0);
    assert_wrong_density_rejected(&drawn, &claimed, wi, UV, N_CHI2);
}

/// The sheet is the same from both sides: mirroring `wi` and `wo` through it changes neither
/// eval nor pdf.
#[test]
fn both_sides_alike() {
    let flip = |v: Vec3| Vec3::new(v.x, v.y, -v.z);
    let mut rng = Pcg32::new(11);
    for props in ["", LEAF, GLASS, MIXED] {
        let b = thin(props);
        for _ in 0..2000 {
            let wi = uniform_direction(rng.next_vec2(), true);
            let wo = uniform_direction(rng.next_vec2(), true);
            assert_eq!(b.eval(wi, wo, UV), b.eval(flip(wi), flip(wo), UV));
            assert_eq!(b.pdf(wi, wo, UV), b.pdf(flip(wi), flip(wo), UV));
        }
    }
}

/// Extreme parameters at random and grazing directions: eval, pdf and sample weights are
/// finite and non-negative, and every sample's weight is `eval / pdf` at its direction.
#[test]
fn finite_at_extremes() {
    let extremes = [
        r#"<float name="roughness" value="0"/><float name="spec_trans" value="1"/>"#,
        r#"<float name="roughness" value="1"/><float name="spec_trans" value="1"/>
           <float name="eta" value="1"/><float name="anisotropic" value="1"/>"#,
        r#"<float name="diff_trans" value="2"/><float name="sheen" value="1"/>
           <float name="sheen_tint" value="1"/><rgb name="base_color" value="0, 0, 0"/>"#,
        r#"<float name="spec_trans" value="0.5"/><float name="eta" value="0.01"/>
           <float name="spec_tint" value="1"/><float name="flatness" value="1"/>"#,
        r#"<float name="diffuse_reflectance_sampling_rate" value="0"/>"#,
    ];
    let grazing = [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, -1.0, 0.0),
        Vec3::new(1.0, 0.0, 1e-7),
        Vec3::new(1.0, 0.0, -1e-7),
        Vec3::Z,
        -Vec3::Z,
    ];
    let mut rng = Pcg32::new(3);
    for props in extremes {
        assert_finite_and_consistent(&thin(props), props, &grazing, UV, &mut rng);
    }
}

/// Sampling reaches everything `eval` gives: the mean sample weight equals the quadrature of
/// `eval` within 4 standard errors plus 1e-3, for sets without sharp lobes. Control: with a
/// diffuse transmission sampling rate of 0 the diffuse transmission is evaluated but never
/// sampled, which must be caught.
#[test]
fn sampled_albedo_equals_quadrature_of_eval() {
    let rough = r#"<float name="spec_trans" value="0.6"/><float name="roughness" value="0.7"/>
        <float name="diff_trans" value="1"/><float name="eta" value="1.4"/>"#;
    let check = |props: &str, deg: f32| AlbedoAgreement::of(&thin(props), dir(deg), UV);
    for (name, props, deg) in [("leaf", LEAF, 30.0), ("rough sheet", rough, 140.0)] {
        let a = check(props, deg);
        println!("{name} at {deg} deg: {a}");
        assert!(a.agrees(), "{name}: {a}");
    }
    let a = check(
        &format!(r#"{LEAF}<float name="diffuse_transmittance_sampling_rate" value="0"/>"#),
        30.0,
    );
    println!("control, transmission never sampled: {a}");
    assert!(a.differs(), "control not caught");
}

/// Every bad parameter is an error located at the property (line 3 of the inline file).
#[test]
fn bad_parameters_are_located_errors() {
    #[rustfmt::skip]
    let cases = [
        ("principledthin", r#"<float name="diff_trans" value="2.5"/>"#, "diff_trans"),
        ("principledthin", r#"<float name="diff_trans" value="-0.5"/>"#, "diff_trans"),
        ("principledthin", r#"<float name="eta" value="0"/>"#, "eta"),
        ("principledthin", r#"<float name="spec_trans" value="1.1"/>"#, "spec_trans"),
        ("principledthin", r#"<float name="specular_transmittance_sampling_rate" value="-1"/>"#, "specular_transmittance_sampling_rate"),
        ("principledthin", r#"<float name="metallic" value="0.5"/>"#, "metallic"),
    ];
    assert_cases_rejected_on_their_line(&cases, false);
}

/// What the path loop is told: it samples with both inputs, has smooth lobes only and is not
/// Lambertian; the textures it reads are reported, switched-off lobes' not.
#[test]
fn traits_and_textures() {
    let b = thin(GLASS);
    assert_smooth_two_input_traits(&b);
    // base colour, roughness, eta; then anisotropic, spec_trans, spec_tint, diff_trans.
    assert_eq!(texture_count(&thin("")), 3);
    assert_eq!(texture_count(&b), 7);
    assert_eq!(
        texture_count(&thin(r#"<float name="diff_trans" value="0"/>"#)),
        3
    );
}

//! `plastic` and `roughplastic` (Mitsuba 3): sampling against the pdf, energy, reciprocity,
//! the coating tables, the back side, and parameter errors. (Agreement of eval and pdf with
//! Mitsuba 3 itself is `bsdf_mitsuba_eval.rs`, on the `plastic*` and `roughplastic*` tables of
//! `tests/bsdf_cases/`.)
//!
//! The chi-square tests (listed in [`N_CHI2`]) run at the Šidák-corrected level of 0.01 over
//! the file; test `k` uses seed `k`. Run with `--nocapture` to see every p-value.

use glam::{Vec2, Vec3};
use tessera_core::bsdf::fresnel::fresnel_dielectric;
use tessera_core::bsdf::microfacet::MicrofacetKind;
use tessera_core::bsdf::plastic_common::fresnel_diffuse_reflectance;
use tessera_core::bsdf::{Bsdf, RoughPlastic};
use tessera_core::texture::Texture;
use tessera_lab::stats::{sampled_albedo, Pcg32};
use tessera_scene::error::InputError;
use tessera_tests::bsdf::{assert_cases_rejected_on_their_line, build_bsdf_xml};
use tessera_tests::bsdf_checks::{
    assert_chi2_cases, assert_wrong_density_rejected, reciprocity_error,
};

/// Chi-square tests in this file: 5 `plastic` cases, 11 `roughplastic` cases.
const N_CHI2: usize = 16;

const UV: Vec2 = Vec2::new(0.25, 0.75);

fn build(xml: &str) -> Result<Bsdf, InputError> {
    build_bsdf_xml(xml, false)
}

fn bsdf(xml: &str) -> Bsdf {
    build(xml).unwrap_or_else(|e| panic!("{e}"))
}

/// A unit direction at polar angle `deg` and azimuth 0.7 rad.
fn dir(deg: f32) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(t.sin() * 0.7f32.cos(), t.sin() * 0.7f32.sin(), t.cos())
}

fn chi2_cases(cases: &[(&str, &str, f32)], first_seed: u64) {
    let cases = cases
        .iter()
        .map(|&(name, xml, deg)| (format!("{name} at {deg} deg"), bsdf(xml), dir(deg)));
    assert_chi2_cases(cases, UV, first_seed, N_CHI2);
}

const PLASTIC_COLOR: &str = r#"<bsdf type="plastic">
    <rgb name="diffuse_reflectance" value="0.2, 0.5, 0.8"/>
    <rgb name="specular_reflectance" value="0.8, 0.9, 0.7"/>
    <float name="int_ior" value="1.9"/><float name="ext_ior" value="1.2"/>
    <boolean name="nonlinear" value="true"/></bsdf>"#;
const PLASTIC_INVERTED: &str = r#"<bsdf type="plastic">
    <float name="int_ior" value="1.0"/><string name="ext_ior" value="water"/></bsdf>"#;

#[test]
fn plastic_samples_its_pdf() {
    let default = r#"<bsdf type="plastic"/>"#;
    chi2_cases(
        &[
            ("default", default, 0.0),
            ("default", default, 45.0),
            ("default", default, 85.0),
            ("colour, nonlinear, eta 1.58", PLASTIC_COLOR, 70.0),
            // Below the critical angle of the inverted interface (41 deg): both components.
            ("eta 0.75", PLASTIC_INVERTED, 30.0),
        ],
        1,
    );
}

#[test]
fn roughplastic_samples_its_pdf() {
    let rough = |dist: &str, alpha: f32, visible: bool, extra: &str| {
        format!(
            r#"<bsdf type="roughplastic"><string name="distribution" value="{dist}"/>
            <float name="alpha" value="{alpha}"/><boolean name="sample_visible" value="{visible}"/>
            {extra}</bsdf>"#
        )
    };
    let colour = r#"<rgb name="diffuse_reflectance" value="0.2, 0.5, 0.8"/>
        <boolean name="nonlinear" value="true"/>"#;
    let dark = r#"<rgb name="diffuse_reflectance" value="0.05, 0.05, 0.05"/>"#;
    let inverted = r#"<float name="int_ior" value="1.1"/><float name="ext_ior" value="1.4"/>"#;
    // (label, material, incidences in degrees): test k (in this order) uses seed 6 + k.
    #[rustfmt::skip]
    let groups = [
        ("beckmann 0.1 visible", rough("beckmann", 0.1, true, ""), &[0.0, 45.0, 85.0][..]),
        ("beckmann 0.5 all normals", rough("beckmann", 0.5, false, colour), &[30.0]),
        ("beckmann 0.05 all normals, dark", rough("beckmann", 0.05, false, dark), &[80.0]),
        ("ggx 0.3 visible, colour", rough("ggx", 0.3, true, colour), &[20.0, 80.0]),
        ("ggx 0.05 all normals, dark", rough("ggx", 0.05, false, dark), &[60.0]),
        ("ggx 0.8 all normals", rough("ggx", 0.8, false, ""), &[87.0]),
        ("ggx 0.2 visible, eta 0.79", rough("ggx", 0.2, true, inverted), &[40.0]),
        ("beckmann 0.3 visible, eta 0.79", rough("beckmann", 0.3, true, inverted), &[75.0]),
    ];
    let cases: Vec<(&str, &str, f32)> = groups
        .iter()
        .flat_map(|(n, x, degs)| degs.iter().map(move |&d| (*n, x.as_str(), d)))
        .collect();
    chi2_cases(&cases, 6);
}

/// Control: the chi-square machinery rejects a plastic whose claimed diffuse probability is
/// wrong (samples of a plastic with diffuse reflectance 0.5, pdf of one with 0.2: the coating
/// is chosen with probability 0.075 instead of 0.167 near normal incidence).
#[test]
fn a_wrong_component_probability_is_rejected() {
    let drawn = bsdf(r#"<bsdf type="plastic"/>"#);
    let claimed =
        bsdf(r#"<bsdf type="plastic"><float name="diffuse_reflectance" value="0.2"/></bsdf>"#);
    let wi = dir(10.0);
    // The non-delta samples of `drawn` against `claimed`'s pdf, then against its own.
    assert_wrong_density_rejected(&drawn, &claimed, wi, UV, N_CHI2);
}

/// White plastic (diffuse and specular reflectance 1). Its exact directional albedo is
/// `F_i + (1 - F_i) (1 - Fdr(eta)) / (eta^2 (1 - Fdr(1/eta)))`, which is 1 for the true `Fdr`;
/// with the published fits Mitsuba 3 uses it is 1 + 1.2e-3 (1 - F_i) at eta = 1.49. The sampled
/// albedo must equal that closed form (within 4 standard errors), and the closed form must be
/// within 1.5e-3 of 1 for indices 1.1 to 1.7.
#[test]
fn white_plastic_albedo_is_one_up_to_the_fdr_fits() {
    for ior in [1.1f32, 1.3, 1.49, 1.7] {
        let xml = format!(
            r#"<bsdf type="plastic"><float name="diffuse_reflectance" value="1"/>
            <float name="int_ior" value="{ior}"/><float name="ext_ior" value="1"/></bsdf>"#
        );
        let b = bsdf(&xml);
        let ratio = (1.0 - fresnel_diffuse_reflectance(ior))
            / (ior * ior * (1.0 - fresnel_diffuse_reflectance(1.0 / ior)));
        for deg in [0.0, 60.0, 89.0] {
            let wi = dir(deg);
            let fi = fresnel_dielectric(wi.z, ior).f;
            let expected = fi + (1.0 - fi) * ratio;
            let (m, se) = sampled_albedo(&b, wi, UV, 200_000, 3);
            println!("ior {ior} at {deg} deg: albedo {m} +- {se}, closed form {expected}");
            assert!((expected - 1.0).abs() < 1.5e-3, "ior {ior}: {expected}");
            for c in 0..3 {
                assert!(
                    (m[c] - expected).abs() <= 4.0 * se[c] + 1e-5,
                    "{m} vs {expected}"
                );
            }
        }
    }
}

/// A white rough plastic reflects at most what arrives: sampled albedo minus 4 standard errors
/// stays at or below 1 (the single-scattering coating loses energy at high roughness; the base
/// term conserves it up to the quadrature of the tables).
#[test]
fn white_roughplastic_albedo_is_at_most_one() {
    for (dist, alpha) in [
        ("beckmann", 0.05),
        ("beckmann", 0.5),
        ("ggx", 0.1),
        ("ggx", 0.9),
    ] {
        let xml = format!(
            r#"<bsdf type="roughplastic"><string name="distribution" value="{dist}"/>
            <float name="alpha" value="{alpha}"/>
            <float name="diffuse_reflectance" value="1"/><boolean name="nonlinear" value="true"/></bsdf>"#
        );
        let b = bsdf(&xml);
        for deg in [0.0, 45.0, 75.0, 88.0] {
            let (m, se) = sampled_albedo(&b, dir(deg), UV, 200_000, 4);
            println!("{dist} {alpha} at {deg} deg: albedo {m} +- {se}");
            assert!(
                m.x - 4.0 * se.x <= 1.0,
                "{dist} {alpha} at {deg}: {m} +- {se}"
            );
        }
    }
}

/// Both Mitsuba plastics are reciprocal: the coating's Fresnel factor depends on `h.wi = h.wo`
/// and the base's on `T(cos theta_i) T(cos theta_o)`. Control: a factor `1 + 0.05 cos theta_i`
/// breaks it and is caught.
#[test]
fn plastics_are_reciprocal() {
    let models = [
        bsdf(PLASTIC_COLOR),
        bsdf(r#"<bsdf type="roughplastic"><float name="alpha" value="0.3"/></bsdf>"#),
        bsdf(
            r#"<bsdf type="roughplastic"><string name="distribution" value="ggx"/>
            <float name="alpha" value="0.1"/><boolean name="sample_visible" value="false"/></bsdf>"#,
        ),
    ];
    for b in &models {
        let e = reciprocity_error(|wi, wo| b.eval(wi, wo, UV), 5, 1e-6);
        println!("reciprocity error {e:.2e}");
        assert!(e < 1e-4, "{e}");
    }
    let b = &models[1];
    let e = reciprocity_error(|wi, wo| b.eval(wi, wo, UV) * (1.0 + 0.05 * wi.z), 5, 1e-6);
    assert!(e > 1e-3, "control not caught: {e}");
}

#[test]
fn back_side_is_black() {
    for b in [bsdf(PLASTIC_COLOR), bsdf(r#"<bsdf type="roughplastic"/>"#)] {
        let (up, down) = (dir(30.0), -dir(50.0));
        assert_eq!(b.eval(down, up, UV), Vec3::ZERO);
        assert_eq!(b.eval(up, down, UV), Vec3::ZERO);
        assert_eq!(b.pdf(down, up, UV), 0.0);
        assert_eq!(b.pdf(up, down, UV), 0.0);
        let mut rng = Pcg32::new(1);
        for _ in 0..1000 {
            assert!(b
                .sample(down, rng.next_f32(), rng.next_vec2(), UV)
                .is_none());
        }
        let nan = Vec3::splat(f32::NAN);
        assert_eq!(b.eval(nan, up, UV), Vec3::ZERO);
        assert!(b.sample(nan, 0.5, Vec2::splat(0.5), UV).is_none());
    }
}

/// The coating tables: transmittance and internal reflectance are fractions, and for a nearly
/// smooth coating (alpha 1e-3) they approach the smooth interface's `1 - F(mu)` (at the
/// table's nodes) and the diffuse Fresnel
/// reflectance of the inside (the latter up to the 64-point rectangle rule over `mu` that
/// Mitsuba uses and the fit's accuracy).
#[test]
fn coating_tables_approach_the_smooth_limit() {
    let white = || Texture::constant(1.0);
    for kind in [MicrofacetKind::Beckmann, MicrofacetKind::Ggx] {
        for eta in [1.2f32, 1.5, 0.8] {
            let rough = RoughPlastic::new(white(), white(), kind, 0.5, true, eta, false);
            let r = rough.internal_reflectance();
            assert!((0.0..1.0).contains(&r), "{r}");
            for i in 0..=20 {
                let t = rough.transmittance(i as f32 / 20.0);
                assert!((0.0..=1.0).contains(&t), "{t}");
            }
            let smooth = RoughPlastic::new(white(), white(), kind, 1e-3, true, eta, false);
            // At the table's nodes, away from grazing and from the critical angle of eta < 1.
            let critical = (1.0 - eta * eta).max(0.0).sqrt();
            for i in 4..64 {
                let mu = i as f32 / 63.0;
                if (mu - critical).abs() < 0.03 {
                    continue;
                }
                let t = smooth.transmittance(mu);
                let want = 1.0 - fresnel_dielectric(mu, eta).f;
                assert!(
                    (t - want).abs() < 2e-3,
                    "{kind:?} eta {eta} mu {mu}: {t} vs {want}"
                );
            }
            let (r, want) = (
                smooth.internal_reflectance(),
                fresnel_diffuse_reflectance(1.0 / eta),
            );
            println!("{kind:?} eta {eta}: R_int {r}, Fdr fit {want}");
            assert!(
                (r - want).abs() < 0.015,
                "{kind:?} eta {eta}: {r} vs {want}"
            );
        }
    }
}

/// Every bad parameter is an error located at the property (line 3 of the inline file).
#[test]
fn bad_parameters_are_located_errors() {
    // (plugin, property line, words the error contains)
    #[rustfmt::skip]
    let cases = [
        ("plastic", r#"<float name="int_ior" value="-1.5"/>"#, "int_ior"),
        ("plastic", r#"<float name="ext_ior" value="0"/>"#, "ext_ior"),
        ("plastic", r#"<string name="int_ior" value="unobtainium"/>"#, "unknown material"),
        ("plastic", r#"<float name="diffuse_reflectance" value="1.2"/>"#, "diffuse_reflectance"),
        ("plastic", r#"<float name="specular_reflectance" value="-0.1"/>"#, "specular_reflectance"),
        ("plastic", r#"<float name="alpha" value="0.1"/>"#, "alpha"),
        ("roughplastic", r#"<float name="alpha" value="-0.1"/>"#, "alpha"),
        ("roughplastic", r#"<float name="alpha" value="0"/>"#, "alpha"),
        ("roughplastic", r#"<string name="distribution" value="phong"/>"#, "distribution"),
        ("roughplastic", r#"<float name="int_ior" value="1.000277"/>"#, "differ"),
        ("roughplastic", r#"<float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.2"/>"#, "isotropic"),
        ("roughplastic", r#"<float name="int_ior" value="0"/>"#, "int_ior"),
    ];
    assert_cases_rejected_on_their_line(&cases, false);
    // Equal alpha_u / alpha_v are the isotropic model.
    let b = build(
        r#"<bsdf type="roughplastic"><float name="alpha_u" value="0.2"/>
        <float name="alpha_v" value="0.2"/></bsdf>"#,
    );
    assert!(b.is_ok());
}

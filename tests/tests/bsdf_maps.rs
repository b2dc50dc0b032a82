//! `normalmap`, `bumpmap` and textured roughness: sampling against the claimed pdf
//! (chi-square), with a control that must fail, and located errors for bad input.
//!
//! The values themselves are compared with Mitsuba 3 in `bsdf_mitsuba_eval.rs` (cases
//! `tests/bsdf_cases/normalmap_*.xml`, `rough*_texture.xml`). The chi-square tests (listed in
//! [`N_CHI2`]) run at the Šidák level `sidak_alpha(0.01, N_CHI2)`; run with `--nocapture` to
//! see the p-values. The normal-mapped tests take BsdfChi2's full 1e6 samples: with half as
//! many, one configuration (the anisotropic conductor at theta_i 60) came out at p = 4.6e-4,
//! and at 4e6 and 1.6e7 samples of the same seed at p = 0.22 and 0.78, a fluctuation. The control judges samples of the normal map against the pdf of the same
//! map with its green channel inverted.
use glam::Vec2;
use std::path::Path;
use tessera_lab::stats::{BsdfChi2, Chi2Result, SphereChi2};
use tessera_tests::bsdf::{
    assert_bad_bsdf as bad, assert_chi2_passes, dir_at as dir, load_bsdf_xml as load,
    CHI2_HALF as CHI2,
};

/// Where the case textures' four pixels around it hold different tilted normals.
const UV: Vec2 = Vec2::new(0.25, 0.75);

/// Chi-square tests in this file: 9 normal-mapped configurations, 3 textured roughnesses and
/// 4 bump-mapped configurations.
const N_CHI2: usize = 16;

fn check_chi2(name: &str, r: &Chi2Result) {
    assert_chi2_passes(name, r, N_CHI2)
}

fn texture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bsdf_cases/textures")
        .join(name)
        .display()
        .to_string()
}

fn normalmap(file: &str, extra: &str, nested: &str) -> String {
    format!(
        r#"<bsdf type="normalmap">{extra}
            <texture name="normalmap" type="bitmap"><boolean name="raw" value="true"/>
            <string name="filename" value="{}"/></texture>{nested}</bsdf>"#,
        texture(file)
    )
}

/// Nested models, with the third incident direction: from below for glass, from the side
/// opposite the tilt for the one-sided models.
const NESTED: [(&str, &str, (f32, f32)); 3] = [
    (
        "anisotropic roughconductor",
        r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/>
        <float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.35"/></bsdf>"#,
        (60.0, 3.8),
    ),
    (
        "roughdielectric",
        r#"<bsdf type="roughdielectric"><float name="alpha" value="0.25"/></bsdf>"#,
        (130.0, 2.0),
    ),
    (
        "roughplastic",
        r#"<bsdf type="roughplastic"><string name="distribution" value="ggx"/>
        <float name="alpha" value="0.2"/></bsdf>"#,
        (60.0, 3.8),
    ),
];

#[test]
fn normalmap_chi2() {
    // Incident directions: near the normal, grazing away from the tilt (where the normals,
    // facing away, are flipped), and the nested model's third.
    let mut k = 0;
    for (name, nested, third) in NESTED {
        let b = load(&normalmap("normal_tilt.png", "", nested));
        for (deg, phi) in [(20.0, 0.7), (85.0, 0.7), third] {
            k += 1;
            let r = BsdfChi2::default().run(&b, dir(deg, phi), UV, k);
            check_chi2(&format!("normalmap over {name}, theta_i {deg}"), &r);
        }
    }
}

#[test]
fn textured_roughness_chi2() {
    let cases = [
        format!(
            r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/>
            <texture name="alpha" type="bitmap"><string name="filename" value="{}"/></texture>
            </bsdf>"#,
            texture("roughness.png")
        ),
        format!(
            r#"<bsdf type="roughdielectric"><boolean name="sample_visible" value="false"/>
            <texture name="alpha_u" type="bitmap"><boolean name="raw" value="true"/>
            <string name="filename" value="{}"/></texture><float name="alpha_v" value="0.08"/>
            </bsdf>"#,
            texture("roughness.png")
        ),
        r#"<bsdf type="roughdielectric"><texture name="alpha" type="checkerboard">
            <rgb name="color0" value="0.05"/><rgb name="color1" value="0.4"/></texture></bsdf>"#
            .to_string(),
    ];
    for (k, xml) in cases.iter().enumerate() {
        let b = load(xml);
        let r = CHI2.run(&b, dir(50.0, 0.4), UV, 100 + k as u64);
        check_chi2(&format!("textured roughness case {k}"), &r);
    }
}

#[test]
fn chi2_control_green_flipped_map_is_rejected() {
    let nested = NESTED[0].1;
    let (a, b) = (
        load(&normalmap("normal_tilt.png", "", nested)),
        load(&normalmap("normal_tilt_green_flipped.png", "", nested)),
    );
    let wi = dir(30.0, 0.7);
    let cfg = SphereChi2 {
        theta_bins: 20,
        phi_bins: 40,
        samples: 300_000,
    };
    let sample = |u: Vec2| a.sample(wi, 0.5, u, UV).map(|s| s.wo);
    let right = cfg.run(sample, |w| f64::from(a.pdf(wi, w, UV)), 5);
    let wrong = cfg.run(sample, |w| f64::from(b.pdf(wi, w, UV)), 5);
    println!("control: right pdf {right}; green flipped {wrong}");
    assert!(right.passes(0.001), "{right}");
    assert!(!wrong.passes(1e-6), "{wrong}");
}

#[test]
fn a_grey_normal_map_gives_no_nan() {
    // (1/2, 1/2, 1/2) is the zero normal, where Mitsuba divides by zero: the unperturbed
    // frame is used instead.
    let b = load(
        r#"<bsdf type="normalmap"><rgb name="normalmap" value="0.5"/>
           <bsdf type="diffuse"/></bsdf>"#,
    );
    let plain = load(r#"<bsdf type="diffuse"/>"#);
    let (wi, wo) = (dir(30.0, 0.2), dir(50.0, 2.0));
    let (v, p) = (b.eval(wi, wo, UV), b.pdf(wi, wo, UV));
    assert!(v.is_finite() && p.is_finite());
    // Unperturbed, so only the (untilted) shadowing term is left: 1.
    assert!(
        (v - plain.eval(wi, wo, UV)).abs().max_element() < 1e-6,
        "{v}"
    );
    assert_eq!(p, plain.pdf(wi, wo, UV));
    assert!(b.sample(wi, 0.5, Vec2::new(0.3, 0.6), UV).is_some());
}

#[test]
fn bad_input_is_located() {
    let err = tessera_tests::bsdf::build_bsdf_xml(
        "<bsdf type=\"normalmap\">\n<bsdf type=\"diffuse\"/>\n</bsdf>",
        false,
    )
    .expect_err("a normal map without its texture is refused")
    .to_string();
    assert!(
        err.contains("case.xml:2:1:") && err.contains("missing parameter \"normalmap\""),
        "{err}"
    );
    bad(
        "roughplastic",
        r#"<texture name="alpha" type="checkerboard"/>"#,
        "alpha",
        "alpha",
    );
}

fn bumpmap(extra: &str, nested: &str) -> String {
    format!(
        r#"<bsdf type="bumpmap">{extra}
            <texture name="height" type="bitmap"><boolean name="raw" value="true"/>
            <string name="filename" value="{}"/></texture>{nested}</bsdf>"#,
        texture("height.png")
    )
}

#[test]
fn bumpmap_chi2() {
    // The flat unit parametrisation (what a bare uv converts to): the tilt is the height's
    // gradient itself, about 0.5 to 1.6 per unit uv at UV for scale 1 (so up to about 60
    // degrees at scale 1.5).
    let cases = [
        (NESTED[0].0, NESTED[0].1, "1.5", (20.0, 0.7)),
        (NESTED[0].0, NESTED[0].1, "1.5", (85.0, 0.7)),
        (NESTED[1].0, NESTED[1].1, "-1", (130.0, 2.0)),
        (NESTED[2].0, NESTED[2].1, "0.7", (60.0, 3.8)),
    ];
    for (k, (name, nested, scale, (deg, phi))) in cases.into_iter().enumerate() {
        let b = load(&bumpmap(
            &format!(r#"<float name="scale" value="{scale}"/>"#),
            nested,
        ));
        let r = BsdfChi2::default().run(&b, dir(deg, phi), UV, 200 + k as u64);
        check_chi2(
            &format!("bumpmap (scale {scale}) over {name}, theta_i {deg}"),
            &r,
        );
    }
}

#[test]
fn degenerate_partials_give_no_nan() {
    // Zero partials (a degenerate uv map) have a zero cross product: the frame stays as it was.
    let b = load(&bumpmap("", r#"<bsdf type="diffuse"/>"#));
    let plain = load(r#"<bsdf type="diffuse"/>"#);
    let zero = tessera_core::geometry::Partials {
        dp_du: glam::Vec3::ZERO,
        dp_dv: glam::Vec3::ZERO,
        ng: glam::Vec3::Z,
        site: None,
    };
    let at = tessera_core::geometry::ShadingPoint {
        uv: UV,
        partials: Some(&zero),
        memo: None,
    };
    let (wi, wo) = (dir(30.0, 0.2), dir(50.0, 2.0));
    let (v, p) = (b.eval(wi, wo, at), b.pdf(wi, wo, at));
    assert!(v.is_finite() && p.is_finite());
    assert!(
        (v - plain.eval(wi, wo, UV)).abs().max_element() < 1e-6,
        "{v}"
    );
    assert_eq!(p, plain.pdf(wi, wo, UV));
    assert!(b.sample(wi, 0.5, Vec2::new(0.3, 0.6), at).is_some());
}

#[test]
fn bad_bumpmap_input_is_located() {
    let cases = [
        (
            "<bsdf type=\"bumpmap\">\n<bsdf type=\"diffuse\"/>\n</bsdf>",
            "case.xml:2:1:",
            "needs exactly one nested texture",
        ),
        (
            "<bsdf type=\"bumpmap\">\n<bsdf type=\"diffuse\"/>\n<texture type=\"checkerboard\"/>\n</bsdf>",
            "case.xml:4:1:",
            "must be a bitmap texture",
        ),
    ];
    for (xml, at, words) in cases {
        let err = tessera_tests::bsdf::build_bsdf_xml(xml, false)
            .expect_err("refused")
            .to_string();
        assert!(err.contains(at) && err.contains(words), "{err}");
    }
    let err = tessera_tests::bsdf::build_bsdf_xml(
        &bumpmap("", "").replace("<bsdf type=\"bumpmap\">", "<bsdf type=\"bumpmap\">\n"),
        false,
    )
    .expect_err("a bump map without a nested bsdf is refused")
    .to_string();
    assert!(err.contains("needs 1 nested bsdf(s), found 0"), "{err}");
}

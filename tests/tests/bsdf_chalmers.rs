//! Chalmers' materials (`blinnphong`, `blinnphong_metal`) and the wrappers `blendbsdf` (alias
//! `blend`) and `mask`: sampling against pdf (chi-square, delta components included), eval/pdf
//! consistency, reciprocity, energy, and the directional albedo of the Blinn-Phong lobe against
//! references computed independently by quadrature (`scripts/blinnphong_albedo.py`, numpy, from
//! the tutorial's formulas).
//!
//! Significance: the file fails with probability 1% if everything is right; each of the
//! [`N_TESTS`] hypothesis tests (chi-square and t) runs at `sidak_alpha(0.01, N_TESTS)`. Each
//! chi-square test uses 1e6 samples with its own seed (its index in [`chi2_cases`]), each
//! t-test 1e6 samples. Controls (not counted) show that a 2%-off density, a blend choosing with
//! the wrong probability and a 1%-off albedo are rejected.

use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_lab::stats::{
    sampled_albedo, sidak_alpha, t_test_mean, BsdfChi2, Chi2Result, Moments, Pcg32, SphereChi2,
};
use tessera_tests::bsdf::{build_bsdf_xml, load_bsdf_xml};

/// Chi-square cases (11) plus albedo t-tests (11).
const N_TESTS: usize = 22;

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

fn bsdf(xml: &str) -> Bsdf {
    load_bsdf_xml(xml)
}

/// The load error of a snippet.
fn error_of(xml: &str) -> String {
    match build_bsdf_xml(xml, false) {
        Ok(_) => panic!("{xml}: loaded"),
        Err(e) => e.to_string(),
    }
}

/// `wi` at `theta` degrees from the normal (azimuth 0.4 rad).
fn dir(theta_deg: f32) -> Vec3 {
    let t = theta_deg.to_radians();
    Vec3::new(t.sin() * 0.4f32.cos(), t.sin() * 0.4f32.sin(), t.cos())
}

const DIFFUSE_08: &str = r#"<bsdf type="diffuse"><float name="reflectance" value="0.8"/></bsdf>"#;

/// (label, material, incident angle in degrees).
fn chi2_cases() -> Vec<(&'static str, String, f32)> {
    let bp = |s: f32, r0: f32, base: &str| {
        format!(
            r#"<bsdf type="blinnphong"><float name="shininess" value="{s}"/><float name="r0" value="{r0}"/>{base}</bsdf>"#
        )
    };
    let metal = |s: f32| {
        format!(
            r#"<bsdf type="blinnphong_metal"><float name="shininess" value="{s}"/><rgb name="color" value="0.9, 0.6, 0.3"/><float name="fresnel" value="0.3"/></bsdf>"#
        )
    };
    vec![
        ("blinnphong s=1, no base", bp(1.0, 0.04, ""), 30.0),
        (
            "blinnphong s=25 over diffuse, normal",
            bp(25.0, 0.04, DIFFUSE_08),
            0.0,
        ),
        (
            "blinnphong s=25 over diffuse",
            bp(25.0, 0.2, DIFFUSE_08),
            60.0,
        ),
        (
            "blinnphong s=300 over diffuse, grazing",
            bp(300.0, 0.04, DIFFUSE_08),
            85.0,
        ),
        (
            "blinnphong s=10 over a mask (delta pass-through)",
            bp(
                10.0,
                0.1,
                &format!(
                    r#"<bsdf type="mask"><float name="opacity" value="0.6"/>{DIFFUSE_08}</bsdf>"#
                ),
            ),
            40.0,
        ),
        ("blinnphong_metal s=50", metal(50.0), 45.0),
        ("blinnphong_metal s=1000, grazing", metal(1000.0), 80.0),
        (
            "blendbsdf diffuse + metal",
            format!(
                r#"<bsdf type="blendbsdf"><float name="weight" value="0.3"/>{DIFFUSE_08}{}</bsdf>"#,
                metal(20.0)
            ),
            40.0,
        ),
        (
            "blend (alias): mask (delta) + twosided diffuse",
            format!(
                r#"<bsdf type="blend"><float name="weight" value="0.6"/><bsdf type="mask"><float name="opacity" value="0.3"/>{}</bsdf><bsdf type="twosided">{DIFFUSE_08}</bsdf></bsdf>"#,
                bp(15.0, 0.04, DIFFUSE_08)
            ),
            70.0,
        ),
        (
            "mask over blinnphong",
            format!(
                r#"<bsdf type="mask"><float name="opacity" value="0.35"/>{}</bsdf>"#,
                bp(40.0, 0.5, DIFFUSE_08)
            ),
            20.0,
        ),
        (
            "mask over twosided diffuse, from below",
            format!(
                r#"<bsdf type="mask"><float name="opacity" value="0.7"/><bsdf type="twosided">{DIFFUSE_08}</bsdf></bsdf>"#
            ),
            150.0,
        ),
    ]
}

fn check(label: &str, r: &Chi2Result) {
    println!("{label}: {r}");
    assert!(r.passes(alpha()), "{label}: {r} (alpha = {:.3e})", alpha());
}

#[test]
fn sampling_matches_pdf() {
    let cases = chi2_cases();
    assert_eq!(cases.len(), 11);
    for (k, (label, xml, theta)) in cases.iter().enumerate() {
        let b = bsdf(xml);
        let r = BsdfChi2::default().run(&b, dir(*theta), Vec2::new(0.3, 0.6), k as u64);
        check(label, &r);
    }
}

#[test]
fn reciprocity() {
    // eval(wi, wo) / |wo.z| == eval(wo, wi) / |wi.z| for every reciprocal model here.
    let mut rng = Pcg32::new(77);
    for (label, xml, _) in chi2_cases() {
        let b = bsdf(&xml);
        let mut checked = 0;
        for _ in 0..2000 {
            let a = tessera_core::sampling::warp::square_to_uniform_sphere(rng.next_vec2());
            let c = tessera_core::sampling::warp::square_to_uniform_sphere(rng.next_vec2());
            let uv = Vec2::new(0.3, 0.6);
            let f1 = b.eval(a, c, uv) / c.z.abs();
            let f2 = b.eval(c, a, uv) / a.z.abs();
            if c.z.abs() < 1e-3 || a.z.abs() < 1e-3 {
                continue;
            }
            checked += 1;
            for k in 0..3 {
                let tol = 1e-4 * f1[k].abs().max(f2[k].abs()) + 1e-6;
                assert!(
                    (f1[k] - f2[k]).abs() <= tol,
                    "{label}: wi {a} wo {c}: {f1} vs {f2}"
                );
            }
        }
        assert!(checked > 1500, "{label}");
    }
}

#[test]
fn white_materials_do_not_create_energy() {
    // Directional albedo (pass-through included) with white parameters, up to grazing.
    let white = [
        r#"<bsdf type="blinnphong"><float name="shininess" value="25"/><float name="r0" value="0"/><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf>"#.to_string(),
        r#"<bsdf type="blinnphong"><float name="shininess" value="1000"/><float name="r0" value="0.04"/><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf>"#.to_string(),
        r#"<bsdf type="blinnphong"><float name="shininess" value="0"/><float name="r0" value="1"/></bsdf>"#.to_string(),
        r#"<bsdf type="blinnphong_metal"><float name="shininess" value="100"/><float name="r0" value="1"/><float name="color" value="1"/></bsdf>"#.to_string(),
        r#"<bsdf type="blend"><float name="weight" value="0.5"/><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf><bsdf type="blinnphong_metal"><float name="r0" value="1"/><float name="color" value="1"/></bsdf></bsdf>"#.to_string(),
        r#"<bsdf type="mask"><float name="opacity" value="0.5"/><bsdf type="blinnphong"><float name="r0" value="0"/><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf></bsdf>"#.to_string(),
    ];
    for xml in &white {
        let b = bsdf(xml);
        for theta in [0.0, 30.0, 60.0, 75.0, 85.0, 89.0] {
            let (m, se) = sampled_albedo(&b, dir(theta), Vec2::ZERO, 200_000, 9);
            let bound = m.x - 4.0 * se.x;
            println!("{xml} theta {theta}: albedo {} +- {}", m.x, se.x);
            assert!(bound <= 1.0, "{xml} at {theta} deg: albedo {m} +- {se}");
        }
    }
}

/// (material, theta, reference albedo per unit colour) from scripts/blinnphong_albedo.py.
fn albedo_cases() -> Vec<(String, f32, f64)> {
    let bp = |s: f32, r0: f32, base: &str| {
        format!(
            r#"<bsdf type="blinnphong"><float name="shininess" value="{s}"/><float name="r0" value="{r0}"/>{base}</bsdf>"#
        )
    };
    let metal = r#"<bsdf type="blinnphong_metal"><float name="shininess" value="50"/><float name="r0" value="0.3"/><float name="color" value="1"/></bsdf>"#;
    vec![
        (bp(1.0, 0.04, ""), 0.0, 0.020182721),
        (bp(1.0, 0.04, ""), 45.0, 0.027416935),
        (bp(1.0, 0.04, ""), 75.0, 0.078345526),
        (bp(20.0, 0.5, DIFFUSE_08), 0.0, 0.685240615),
        (bp(20.0, 0.5, DIFFUSE_08), 40.0, 0.671563140),
        (bp(20.0, 0.5, DIFFUSE_08), 80.0, 0.677582774),
        (bp(200.0, 1.0, ""), 10.0, 1.000000003),
        (bp(200.0, 1.0, ""), 60.0, 0.999019950),
        (bp(200.0, 1.0, ""), 85.0, 0.937481594),
        (metal.to_string(), 30.0, 0.299771028),
        (metal.to_string(), 70.0, 0.347136236),
    ]
}

/// Sampled albedo (red channel) as moments.
fn albedo_moments(b: &Bsdf, wi: Vec3, n: usize, seed: u64) -> Moments {
    let mut rng = Pcg32::new(seed);
    let mut m = Moments::new();
    for _ in 0..n {
        let u1 = rng.next_f32();
        let u2 = rng.next_vec2();
        let w = b
            .sample(wi, u1, u2, Vec2::ZERO)
            .map_or(0.0, |s| f64::from(s.weight.x));
        m.push(w);
    }
    m
}

#[test]
fn albedo_matches_quadrature() {
    let cases = albedo_cases();
    assert_eq!(cases.len() + 11, N_TESTS);
    for (k, (xml, theta, want)) in cases.iter().enumerate() {
        let b = bsdf(xml);
        let m = albedo_moments(&b, dir(*theta), 1_000_000, 100 + k as u64);
        let t = t_test_mean(&m, *want);
        println!("{xml} theta {theta}: {} vs {want}: {t}", m.mean());
        assert!(
            t.passes(alpha()),
            "{xml} theta {theta}: {} vs {want}: {t}",
            m.mean()
        );
    }
}

#[test]
fn controls_reject_wrong_models() {
    // A 2% wider lobe's density (shininess 25 sampled, 24.5 claimed).
    let a = bsdf(r#"<bsdf type="blinnphong_metal"><float name="shininess" value="25"/></bsdf>"#);
    let b = bsdf(r#"<bsdf type="blinnphong_metal"><float name="shininess" value="24.5"/></bsdf>"#);
    let wi = dir(30.0);
    let r = SphereChi2 {
        theta_bins: 20,
        phi_bins: 40,
        samples: 1_000_000,
    }
    .run(
        |u| a.sample(wi, 0.5, u, Vec2::ZERO).map(|s| s.wo),
        |w| f64::from(b.pdf(wi, w, Vec2::ZERO)),
        500,
    );
    println!("control, shininess 25 vs 24.5: {r}");
    assert!(!r.passes(alpha()), "a wrong lobe passed: {r}");
    // A blend sampled with weight 0.3 but claiming 0.33.
    let blend = |w: f32| {
        bsdf(&format!(
            r#"<bsdf type="blendbsdf"><float name="weight" value="{w}"/>{DIFFUSE_08}<bsdf type="blinnphong_metal"><float name="shininess" value="60"/></bsdf></bsdf>"#
        ))
    };
    let (a, b) = (blend(0.3), blend(0.33));
    let mut rng = Pcg32::new(501);
    let r = SphereChi2 {
        theta_bins: 20,
        phi_bins: 40,
        samples: 1_000_000,
    }
    .run(
        |u| a.sample(wi, rng.next_f32(), u, Vec2::ZERO).map(|s| s.wo),
        |w| f64::from(b.pdf(wi, w, Vec2::ZERO)),
        502,
    );
    println!("control, blend weight 0.3 vs 0.33: {r}");
    assert!(!r.passes(alpha()), "a wrong blend weight passed: {r}");
    // A reference 1% off.
    let (xml, theta, want) = &albedo_cases()[4];
    let m = albedo_moments(&bsdf(xml), dir(*theta), 1_000_000, 104);
    let t = t_test_mean(&m, want * 1.01);
    println!("control, albedo reference 1% high: {t}");
    assert!(!t.passes(alpha()), "a 1% wrong albedo passed: {t}");
}

#[test]
fn the_tutorial_names_and_defaults() {
    // r0 and fresnel are one parameter; blend and blendbsdf one plugin; defaults as documented.
    let wi = dir(35.0);
    let wo = dir(-20.0);
    let uv = Vec2::ZERO;
    let a = bsdf(
        r#"<bsdf type="blinnphong"><float name="fresnel" value="0.04"/><float name="shininess" value="25"/></bsdf>"#,
    );
    let b = bsdf(r#"<bsdf type="blinnphong"/>"#);
    assert_eq!(a.eval(wi, wo, uv), b.eval(wi, wo, uv));
    assert!(b.eval(wi, wo, uv).x > 0.0);
    let c = bsdf(&format!(
        r#"<bsdf type="blend">{DIFFUSE_08}<bsdf type="blinnphong"/></bsdf>"#
    ));
    let d = bsdf(&format!(
        r#"<bsdf type="blendbsdf"><float name="weight" value="0.5"/>{DIFFUSE_08}<bsdf type="blinnphong"/></bsdf>"#
    ));
    assert_eq!(c.eval(wi, wo, uv), d.eval(wi, wo, uv));
    // Chalmers' LinearBlend(w, a, b) = w a + (1 - w) b: the weight belongs to the second.
    let e = bsdf(
        r#"<bsdf type="blend"><float name="weight" value="0.25"/><bsdf type="diffuse"><float name="reflectance" value="0"/></bsdf><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf>"#,
    );
    let f = e.eval(Vec3::Z, Vec3::Z, uv).x;
    assert!((f - 0.25 / std::f32::consts::PI).abs() < 1e-7, "{f}");
    // The back side of the one-sided models scatters nothing.
    for m in [&a, &b, &c] {
        assert_eq!(m.eval(-wi, wo, uv), Vec3::ZERO);
        assert!(m.sample(-wi, 0.3, Vec2::new(0.2, 0.7), uv).is_none());
    }
}

#[test]
fn bad_parameters_are_located_errors() {
    let cases = [
        (
            r#"<bsdf type="blendbsdf"><float name="weight" value="1.2"/><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
            "<float name=\"weight\"",
            "\"weight\" of bsdf \"blendbsdf\" must be in [0, 1]",
        ),
        (
            r#"<bsdf type="blend"><float name="weight" value="-0.1"/><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
            "<float name=\"weight\"",
            "must be in [0, 1]",
        ),
        (
            r#"<bsdf type="blendbsdf"><bsdf type="diffuse"/></bsdf>"#,
            "<bsdf type=\"blendbsdf\"",
            "needs 2 nested bsdf(s), found 1",
        ),
        (
            r#"<bsdf type="blendbsdf"><bsdf type="diffuse"/><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
            "<bsdf type=\"blendbsdf\"",
            "needs 2 nested bsdf(s), found 3",
        ),
        (
            r#"<bsdf type="mask"><float name="opacity" value="2"/><bsdf type="diffuse"/></bsdf>"#,
            "<float name=\"opacity\"",
            "\"opacity\" of bsdf \"mask\" must be in [0, 1]",
        ),
        (
            r#"<bsdf type="mask"/>"#,
            "<bsdf type=\"mask\"",
            "needs 1 nested bsdf(s), found 0",
        ),
        (
            r#"<bsdf type="blinnphong"><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
            "<bsdf type=\"blinnphong\"",
            "needs 0 to 1 nested bsdf(s), found 2",
        ),
        (
            r#"<bsdf type="blinnphong_metal"><bsdf type="diffuse"/></bsdf>"#,
            "<bsdf type=\"blinnphong_metal\"",
            "needs 0 nested bsdf(s), found 1",
        ),
        (
            r#"<bsdf type="blinnphong"><float name="shininess" value="-1"/></bsdf>"#,
            "<float name=\"shininess\"",
            "\"shininess\" of bsdf \"blinnphong\" must be in [0, 1e6]",
        ),
        (
            r#"<bsdf type="blinnphong"><float name="r0" value="1.5"/></bsdf>"#,
            "<float name=\"r0\"",
            "\"r0\" of bsdf \"blinnphong\" must be in [0, 1]",
        ),
        (
            r#"<bsdf type="blinnphong"><float name="r0" value="0.5"/><float name="fresnel" value="0.5"/></bsdf>"#,
            "<float name=\"fresnel\"",
            "not both",
        ),
        (
            r#"<bsdf type="blinnphong_metal"><rgb name="color" value="1.2, 0.5, 0.5"/></bsdf>"#,
            "<rgb name=\"color\"",
            "\"color\" of bsdf \"blinnphong_metal\" must be in [0, 1]",
        ),
        (
            r#"<bsdf type="blinnphong"><float name="exponent" value="3"/></bsdf>"#,
            "<float name=\"exponent\"",
            "unused parameter \"exponent\"",
        ),
    ];
    for (xml, marker, needle) in cases {
        let col = xml.find(marker).expect("marker") + 1;
        let at = format!("case.xml:2:{col}: ");
        let e = error_of(xml);
        assert!(
            e.contains(&at) && e.contains(needle),
            "{xml}\n  -> {e} (expected {at}...{needle})"
        );
    }
}

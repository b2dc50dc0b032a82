//! Wakame's `microfacet` and Nori's `mirror`, loaded from Nori-dialect XML: sampling against
//! the pdf (chi-square), directional albedo against an independent quadrature (Student
//! t-tests), energy, reciprocity, the back side, and parameter errors.
//!
//! Significance: the chi-square tests ([`N_CHI2`]) and the t-tests ([`N_TTESTS`]) each run at
//! the Šidák-corrected level of 0.01 over their group; run with `--nocapture` to see the
//! p-values.

use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_core::math::Norm;
use tessera_lab::stats::{sampled_albedo, sidak_alpha, t_test_mean, Moments, Pcg32};
use tessera_scene::error::InputError;
use tessera_tests::bsdf::{assert_cases_rejected_on_their_line, build_bsdf_xml};
use tessera_tests::bsdf_checks::{assert_chi2_cases, chi2_against_density, reciprocity_error};

/// Chi-square tests of `microfacet` sampling.
const N_CHI2: usize = 7;
/// Albedo t-tests: 12 with grey kd (one channel), 4 x 3 channels with coloured kd.
const N_TTESTS: usize = 24;

const UV: Vec2 = Vec2::new(0.25, 0.75);

fn build(xml: &str) -> Result<Bsdf, InputError> {
    build_bsdf_xml(xml, true)
}

fn bsdf(xml: &str) -> Bsdf {
    build(xml).unwrap_or_else(|e| panic!("{e}"))
}

fn microfacet(alpha: f32, kd: [f32; 3]) -> Bsdf {
    bsdf(&format!(
        r#"<bsdf type="microfacet"><float name="alpha" value="{alpha}"/>
        <float name="intIOR" value="1.5046"/><float name="extIOR" value="1.000277"/>
        <color name="kd" value="{}, {}, {}"/></bsdf>"#,
        kd[0], kd[1], kd[2]
    ))
}

/// A unit direction at polar angle `deg` and azimuth 2.1 rad.
fn dir(deg: f32) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(t.sin() * 2.1f32.cos(), t.sin() * 2.1f32.sin(), t.cos())
}

#[test]
fn microfacet_samples_its_pdf() {
    let cases: [(f32, [f32; 3], f32); N_CHI2] = [
        (0.1, [0.5; 3], 0.0),
        (0.1, [0.5; 3], 45.0),
        (0.1, [0.5; 3], 85.0),
        (0.3, [0.2, 0.6, 0.4], 30.0),
        (0.3, [0.2, 0.6, 0.4], 80.0),
        (0.6, [0.0; 3], 60.0),
        (0.05, [0.2; 3], 89.0),
    ];
    let cases = cases.map(|(alpha, kd, deg)| {
        let label = format!("alpha {alpha} kd {kd:?} at {deg} deg");
        (label, microfacet(alpha, kd), dir(deg))
    });
    assert_chi2_cases(cases, UV, 1, N_CHI2);
}

/// Control: samples of alpha 0.3 against the pdf of alpha 0.36 are rejected.
#[test]
fn a_wrong_roughness_is_rejected() {
    let (drawn, claimed) = (microfacet(0.3, [0.0; 3]), microfacet(0.36, [0.0; 3]));
    let wi = dir(30.0);
    // (The microfacet's samples are never delta, so every sample is judged.)
    let r = chi2_against_density(&drawn, &claimed, wi, UV, 3, 8);
    println!("control: {r}");
    assert!(!r.passes(sidak_alpha(0.01, N_CHI2)), "{r}");
}

/// Specular albedo `S(theta_i)` (the integral of `D F G / (4 cos_i cos_o) cos_o`) for
/// `int_ior = 1.5046`, `ext_ior = 1.000277`, by `scripts/wakame_microfacet_albedo.py`
/// (numpy quadrature of the assignment's formula, two independent rules agreeing to 1e-7):
/// `(alpha, [S at 0, 30, 60, 80 degrees])`.
const SPECULAR_ALBEDO: [(f32, [f64; 4]); 3] = [
    (0.1, [0.0405396, 0.0423177, 0.0915714, 0.3203674]),
    (0.3, [0.0407564, 0.0438710, 0.0776786, 0.1808518]),
    (0.6, [0.0358482, 0.0376013, 0.0554415, 0.1053633]),
];
const THETAS: [f32; 4] = [0.0, 30.0, 60.0, 80.0];

/// Mean sampled weight per channel (failed samples count as 0) over `n` draws.
fn albedo_moments(b: &Bsdf, wi: Vec3, n: usize, seed: u64) -> [Moments; 3] {
    let mut rng = Pcg32::new(seed);
    let mut m = [Moments::new(), Moments::new(), Moments::new()];
    for _ in 0..n {
        let w = b
            .sample(wi, rng.next_f32(), rng.next_vec2(), UV)
            .map_or(Vec3::ZERO, |s| s.weight);
        for c in 0..3 {
            m[c].push(f64::from(w[c]));
        }
    }
    m
}

/// The sampled directional albedo equals `kd + ks S(theta_i)` (Student t-tests).
#[test]
fn microfacet_albedo_matches_quadrature() {
    let a = sidak_alpha(0.01, N_TTESTS);
    let mut failed = Vec::new();
    let mut check = |what: String, m: &Moments, reference: f64| {
        let t = t_test_mean(m, reference);
        println!("{what}: mean {:.6} reference {reference:.6}: {t}", m.mean());
        if !t.passes(a) {
            failed.push(format!("{what}: mean {} vs {reference}: {t}", m.mean()));
        }
    };
    let mut seed = 100;
    for &(alpha, s) in &SPECULAR_ALBEDO {
        let b = microfacet(alpha, [0.5; 3]);
        for (i, &deg) in THETAS.iter().enumerate() {
            seed += 1;
            let m = albedo_moments(&b, dir(deg), 200_000, seed);
            check(
                format!("alpha {alpha}, kd 0.5 at {deg}"),
                &m[0],
                0.5 + 0.5 * s[i],
            );
        }
    }
    let kd = [0.1f32, 0.3, 0.2];
    let b = microfacet(0.3, kd);
    for (i, &deg) in THETAS.iter().enumerate() {
        seed += 1;
        let m = albedo_moments(&b, dir(deg), 200_000, seed);
        for c in 0..3 {
            let reference = f64::from(kd[c]) + 0.7 * SPECULAR_ALBEDO[1].1[i];
            check(
                format!("alpha 0.3, kd {kd:?}[{c}] at {deg}"),
                &m[c],
                reference,
            );
        }
    }
    assert!(failed.is_empty(), "alpha = {a:.3e}:\n{}", failed.join("\n"));
}

/// Control: the same t-test rejects an albedo off by 1% (the alpha 0.3, normal incidence
/// reference scaled by 1.01).
#[test]
fn a_wrong_albedo_is_rejected() {
    let b = microfacet(0.3, [0.5; 3]);
    let m = albedo_moments(&b, dir(0.0), 200_000, 7);
    let reference = 1.01 * (0.5 + 0.5 * SPECULAR_ALBEDO[1].1[0]);
    let t = t_test_mean(&m[0], reference);
    println!("control: {t}");
    assert!(!t.passes(sidak_alpha(0.01, N_TTESTS)), "{t}");
}

/// With white or black kd (ks = 0 or 1) and in between, at most what arrives is reflected.
#[test]
fn microfacet_albedo_is_at_most_one() {
    for alpha in [0.05f32, 0.3, 1.0] {
        for kd in [[0.0f32; 3], [0.5; 3], [1.0; 3]] {
            let b = microfacet(alpha, kd);
            for deg in [0.0, 50.0, 80.0, 89.0] {
                let (m, se) = sampled_albedo(&b, dir(deg), UV, 100_000, 9);
                assert!(
                    m.max_element() - 4.0 * se.max_element() <= 1.0 + 1e-5,
                    "alpha {alpha} kd {kd:?} at {deg}: {m} +- {se}"
                );
            }
        }
    }
}

/// `f(wi, wo) = f(wo, wi)`; control: a factor `1 + 0.05 cos theta_i` is caught.
#[test]
fn microfacet_is_reciprocal() {
    let b = microfacet(0.2, [0.3, 0.1, 0.2]);
    // (No floor under the denominator: the microfacet is never black on the front side.)
    let err = |scale: &dyn Fn(Vec3) -> f32| {
        reciprocity_error(|wi, wo| b.eval(wi, wo, UV) * scale(wi), 11, 0.0)
    };
    let e = err(&|_| 1.0);
    println!("reciprocity error {e:.2e}");
    assert!(e < 1e-4, "{e}");
    assert!(err(&|w| 1.0 + 0.05 * w.z) > 1e-3);
}

#[test]
fn back_side_is_black() {
    let b = microfacet(0.2, [0.5; 3]);
    let (up, down) = (dir(30.0), -dir(40.0));
    assert_eq!(b.eval(down, up, UV), Vec3::ZERO);
    assert_eq!(b.eval(up, down, UV), Vec3::ZERO);
    assert_eq!(b.pdf(down, up, UV), 0.0);
    let mut rng = Pcg32::new(2);
    for _ in 0..1000 {
        assert!(b
            .sample(down, rng.next_f32(), rng.next_vec2(), UV)
            .is_none());
        let m = bsdf(r#"<bsdf type="mirror"/>"#);
        assert!(m
            .sample(down, rng.next_f32(), rng.next_vec2(), UV)
            .is_none());
    }
    assert_eq!(b.eval(Vec3::splat(f32::NAN), up, UV), Vec3::ZERO);
}

/// The mirror: the reflected direction with weight 1 and probability 1 for any random
/// numbers, nothing smooth.
#[test]
fn mirror_reflects_everything() {
    let m = bsdf(r#"<bsdf type="mirror"/>"#);
    assert!(m.has_delta() && !m.has_smooth());
    let mut rng = Pcg32::new(4);
    for deg in [0.0, 30.0, 75.0, 89.9] {
        let wi = dir(deg);
        for _ in 0..100 {
            let s = m.sample(wi, rng.next_f32(), rng.next_vec2(), UV).unwrap();
            assert!(s.delta && s.pdf == 1.0 && s.eta == 1.0);
            assert_eq!(s.weight, Vec3::ONE);
            assert!((s.wo - Vec3::new(-wi.x, -wi.y, wi.z)).norm() < 1e-6);
            assert_eq!(m.eval(wi, s.wo, UV), Vec3::ZERO);
            assert_eq!(m.pdf(wi, s.wo, UV), 0.0);
        }
    }
}

/// Nori's defaults (intIOR 1.5046, extIOR 1.000277, kd 0.5, alpha 0.1) are the loader's.
#[test]
fn defaults_are_noris() {
    let (a, b) = (
        bsdf(r#"<bsdf type="microfacet"/>"#),
        microfacet(0.1, [0.5; 3]),
    );
    let (wi, wo) = (dir(20.0), dir(-35.0));
    assert_eq!(a.eval(wi, wo, UV), b.eval(wi, wo, UV));
    assert_eq!(a.pdf(wi, wo, UV), b.pdf(wi, wo, UV));
}

/// Every bad parameter is an error located at the property (line 3 of the inline file).
#[test]
fn bad_parameters_are_located_errors() {
    let cases = [
        (
            "microfacet",
            r#"<float name="alpha" value="-0.1"/>"#,
            "alpha",
        ),
        ("microfacet", r#"<float name="alpha" value="0"/>"#, "alpha"),
        (
            "microfacet",
            r#"<float name="intIOR" value="0"/>"#,
            "int_ior",
        ),
        (
            "microfacet",
            r#"<float name="extIOR" value="-1"/>"#,
            "ext_ior",
        ),
        (
            "microfacet",
            r#"<color name="kd" value="0.5, 1.2, 0.5"/>"#,
            "kd",
        ),
        (
            "microfacet",
            r#"<color name="kd" value="0.5, -0.2, 0.5"/>"#,
            "kd",
        ),
        (
            "microfacet",
            r#"<float name="roughness" value="0.1"/>"#,
            "roughness",
        ),
        (
            "mirror",
            r#"<color name="albedo" value="0.5, 0.5, 0.5"/>"#,
            "albedo",
        ),
    ];
    assert_cases_rejected_on_their_line(&cases, true);
}

//! `dielectric`, `thindielectric` and `roughdielectric`: sampling against the pdf (delta
//! components by their probabilities), agreement with Mitsuba 3's samples, energy, the
//! generalized reciprocity of refraction, total internal reflection, and located errors.
//!
//! Materials are built from Mitsuba 3 XML through the loader. The chi-square tests (counted in
//! [`N_CHI2`]) run at the Šidák level `sidak_alpha(0.01, N_CHI2)` with seeds 1..=N_CHI2; run
//! with `--nocapture` to see the p-values. Eval and pdf values are compared with Mitsuba in
//! `bsdf_mitsuba_eval.rs` (cases `tests/bsdf_cases/*dielectric*.xml`, both sides).
//!
//! Energy: in radiance mode a refraction into the denser medium scales the weight by
//! `1 / eta^2`, so the sampled albedo is not bounded by 1 from inside. The tests therefore
//! undo the scaling (weight times `sample.eta^2` for refractions): that sum must have mean <= 1,
//! and exactly 1 for the smooth interface. Controls: a 3% wrong index for the chi-square test,
//! a wrong index for the Mitsuba sample table, a plain (non-generalized) reciprocity check.

// Reference values are kept as the reference renderer printed them.
#![allow(clippy::excessive_precision)]
use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_core::math::Norm;
use tessera_lab::stats::{BsdfChi2, Chi2Result, Pcg32, SphereChi2};
use tessera_tests::bsdf::{
    assert_bad_bsdf as bad, assert_chi2_passes, dir_at as dir, load_bsdf_xml as load, rough_xml,
    uniform_direction, CHI2_HALF as CHI2,
};

const UV: Vec2 = Vec2::new(0.25, 0.75);

/// Chi-square tests in this file: 5 smooth dielectric and 2 thin-sheet incidences, 9 rough
/// configurations.
const N_CHI2: usize = 16;

/// The smooth models have two delta bins: few samples suffice.
const CHI2_DELTA: BsdfChi2 = BsdfChi2 {
    theta_bins: 20,
    phi_bins: 40,
    samples: 100_000,
};

const TINTS: &str = r#"<rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/>
    <rgb name="specular_transmittance" value="0.3, 0.6, 0.9"/>"#;

fn check_chi2(name: &str, r: &Chi2Result) {
    assert_chi2_passes(name, r, N_CHI2)
}

fn rough(dist: &str, au: f32, av: f32, visible: bool, extra: &str) -> String {
    rough_xml("roughdielectric", dist, au, av, visible, extra)
}

fn smooth(plugin: &str, extra: &str) -> String {
    format!(r#"<bsdf type="{plugin}"> {extra} </bsdf>"#)
}

/// Mitsuba 3.9.1 `scalar_rgb` samples with `u2` = (0.5, 0.5): wi, u1, wo, weight, pdf, eta
/// (all zero = no sample). Made with `b.sample(mi.BSDFContext(), si, u1, (0.5, 0.5))` on
/// `si.wi = wi`, `si.sh_frame` = identity, for the materials of [`mitsuba_case`].
#[rustfmt::skip]
const MITSUBA_SAMPLES: &[(&str, [f32; 12])] = &[
    ("dielectric", [0.132813452, 0.111867227, 0.984807753, 0.001, -0.132813454, -0.111867227, 0.98480773, 0.899999976, 0.800000012, 0.699999988, 0.0405519381, 1.0]),
    ("dielectric", [0.132813452, 0.111867227, 0.984807753, 0.999, -0.0882960632, -0.0743707418, -0.993314028, 0.132592753, 0.265185505, 0.397778243, 0.95944804, 1.50418329]),
    ("dielectric", [0.662372764, 0.557908883, 0.5, 0.001, -0.662372768, -0.557908893, 0.5, 0.899999976, 0.800000012, 0.699999988, 0.0898798928, 1.0]),
    ("dielectric", [0.662372764, 0.557908883, 0.5, 0.999, -0.440353781, -0.370904863, -0.817629576, 0.132592753, 0.265185505, 0.397778243, 0.91012013, 1.50418329]),
    ("dielectric", [0.761931732, 0.641766244, 0.0871557427, 0.001, -0.761931717, -0.64176625, 0.0871557444, 0.899999976, 0.800000012, 0.699999988, 0.61326164, 1.0]),
    ("dielectric", [0.761931732, 0.641766244, 0.0871557427, 0.999, -0.506541848, -0.426654309, -0.749253929, 0.132592753, 0.265185505, 0.397778243, 0.38673836, 1.50418329]),
    ("dielectric", [0.585903107, 0.493499379, -0.64278761, 0.001, -0.585903108, -0.493499368, -0.642787635, 0.899999976, 0.800000012, 0.699999988, 1.0, 1.0]),
    ("dielectric", [0.585903107, 0.493499379, -0.64278761, 0.999, -0.585903108, -0.493499368, -0.642787635, 0.899999976, 0.800000012, 0.699999988, 1.0, 1.0]),
    ("dielectric", [0.0666603889, 0.056147271, -0.996194698, 0.001, -0.0666603893, -0.0561472699, -0.99619472, 0.899999976, 0.800000012, 0.699999988, 0.0405413136, 1.0]),
    ("dielectric", [0.0666603889, 0.056147271, -0.996194698, 0.999, -0.100269444, -0.0844557881, 0.991369426, 0.678770185, 1.35754037, 2.03631043, 0.959458709, 0.664812624]),
    ("dielectric_inv", [0.132813452, 0.111867227, 0.984807753, 0.001, -0.132813454, -0.111867227, 0.98480773, 1.0, 1.0, 1.0, 0.0200930145, 1.0]),
    ("dielectric_inv", [0.132813452, 0.111867227, 0.984807753, 0.999, -0.176641896, -0.148783416, -0.972965062, 1.76890016, 1.76890016, 1.76890016, 0.979906976, 0.751879692]),
    ("dielectric_inv", [0.662372764, 0.557908883, 0.5, 0.001, -0.662372768, -0.557908893, 0.5, 1.0, 1.0, 1.0, 1.0, 1.0]),
    ("dielectric_inv", [0.662372764, 0.557908883, 0.5, 0.999, -0.662372768, -0.557908893, 0.5, 1.0, 1.0, 1.0, 1.0, 1.0]),
    ("dielectric_inv", [0.761931732, 0.641766244, 0.0871557427, 0.001, -0.761931717, -0.64176625, 0.0871557444, 1.0, 1.0, 1.0, 1.0, 1.0]),
    ("dielectric_inv", [0.761931732, 0.641766244, 0.0871557427, 0.999, -0.761931717, -0.64176625, 0.0871557444, 1.0, 1.0, 1.0, 1.0, 1.0]),
    ("dielectric_inv", [0.585903107, 0.493499379, -0.64278761, 0.001, -0.585903108, -0.493499368, -0.642787635, 1.0, 1.0, 1.0, 0.0332498737, 1.0]),
    ("dielectric_inv", [0.585903107, 0.493499379, -0.64278761, 0.999, -0.440528661, -0.371052146, 0.817468584, 0.565323055, 0.565323055, 0.565323055, 0.966750145, 1.33000004]),
    ("dielectric_inv", [0.0666603889, 0.056147271, -0.996194698, 0.001, -0.0666603893, -0.0561472699, -0.99619472, 1.0, 1.0, 1.0, 0.0200599525, 1.0]),
    ("dielectric_inv", [0.0666603889, 0.056147271, -0.996194698, 0.999, -0.0501205921, -0.0422159918, 0.997850597, 0.565323055, 0.565323055, 0.565323055, 0.979940057, 1.33000004]),
    ("thindielectric", [0.132813452, 0.111867227, 0.984807753, 0.001, -0.132813454, -0.111867227, 0.98480773, 0.899999976, 0.800000012, 0.699999988, 0.0398785397, 1.0]),
    ("thindielectric", [0.132813452, 0.111867227, 0.984807753, 0.999, -0.132813454, -0.111867227, -0.98480773, 0.300000012, 0.600000024, 0.899999976, 0.960121453, 1.0]),
    ("thindielectric", [0.662372764, 0.557908883, 0.5, 0.001, -0.662372768, -0.557908893, 0.5, 0.899999976, 0.800000012, 0.699999988, 0.112533398, 1.0]),
    ("thindielectric", [0.662372764, 0.557908883, 0.5, 0.999, -0.662372768, -0.557908893, -0.5, 0.300000012, 0.600000024, 0.899999976, 0.887466609, 1.0]),
    ("thindielectric", [0.761931732, 0.641766244, 0.0871557427, 0.001, -0.761931717, -0.64176625, 0.0871557444, 0.899999976, 0.800000012, 0.699999988, 0.736916304, 1.0]),
    ("thindielectric", [0.761931732, 0.641766244, 0.0871557427, 0.999, -0.761931717, -0.64176625, -0.0871557444, 0.300000012, 0.600000024, 0.899999976, 0.263083696, 1.0]),
    ("thindielectric", [0.585903107, 0.493499379, -0.64278761, 0.001, -0.585903108, -0.493499368, -0.642787635, 0.899999976, 0.800000012, 0.699999988, 0.0650461465, 1.0]),
    ("thindielectric", [0.585903107, 0.493499379, -0.64278761, 0.999, -0.585903108, -0.493499368, 0.642787635, 0.300000012, 0.600000024, 0.899999976, 0.934953868, 1.0]),
    ("thindielectric", [0.0666603889, 0.056147271, -0.996194698, 0.001, -0.0666603893, -0.0561472699, -0.99619472, 0.899999976, 0.800000012, 0.699999988, 0.0398596674, 1.0]),
    ("thindielectric", [0.0666603889, 0.056147271, -0.996194698, 0.999, -0.0666603893, -0.0561472699, 0.99619472, 0.300000012, 0.600000024, 0.899999976, 0.960140347, 1.0]),
];

/// The materials of [`MITSUBA_SAMPLES`].
fn mitsuba_case(name: &str) -> String {
    match name {
        "dielectric" => smooth("dielectric", TINTS),
        "dielectric_inv" => smooth(
            "dielectric",
            r#"<float name="int_ior" value="1.0"/> <float name="ext_ior" value="1.33"/>"#,
        ),
        "thindielectric" => smooth(
            "thindielectric",
            &format!(r#"<string name="int_ior" value="water"/> {TINTS}"#),
        ),
        _ => unreachable!("{name}"),
    }
}

/// Rows of [`MITSUBA_SAMPLES`] named `which` that `b` disagrees with.
fn sample_mismatches(b: &Bsdf, which: &str) -> Vec<String> {
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * a.abs().max(b.abs()) + 1e-6;
    let mut bad = Vec::new();
    for (_, v) in MITSUBA_SAMPLES.iter().filter(|(n, _)| *n == which) {
        let wi = Vec3::new(v[0], v[1], v[2]);
        let got = b.sample(wi, v[3], Vec2::splat(0.5), UV);
        let ok = match got {
            None => v[10] == 0.0,
            Some(s) => {
                let have = [
                    s.wo.x, s.wo.y, s.wo.z, s.weight.x, s.weight.y, s.weight.z, s.pdf, s.eta,
                ];
                s.delta && v[4..].iter().zip(have).all(|(&w, h)| close(w, h))
            }
        };
        if !ok {
            bad.push(format!(
                "{which}: wi {wi} u1 {}: {got:?}, Mitsuba {v:?}",
                v[3]
            ));
        }
    }
    bad
}

#[test]
fn smooth_samples_match_mitsuba() {
    for which in ["dielectric", "dielectric_inv", "thindielectric"] {
        let bad = sample_mismatches(&load(&mitsuba_case(which)), which);
        assert!(bad.is_empty(), "{}", bad.join("\n"));
    }
    // Control: glass of index 1.6 is not BK7.
    let wrong = smooth(
        "dielectric",
        &format!(r#"<float name="int_ior" value="1.6"/> {TINTS}"#),
    );
    assert!(!sample_mismatches(&load(&wrong), "dielectric").is_empty());
}

#[test]
fn smooth_chi2() {
    let inverted = r#"<float name="int_ior" value="1.0"/> <float name="ext_ior" value="1.33"/>"#;
    let water = r#"<string name="int_ior" value="water"/>"#;
    let cases = [
        ("dielectric", TINTS, 0.0),
        ("dielectric", TINTS, 45.0),
        ("dielectric", "", 80.0),
        ("dielectric", TINTS, 150.0),
        ("dielectric", inverted, 30.0),
        ("thindielectric", water, 30.0),
        ("thindielectric", TINTS, 150.0),
    ];
    for (k, (plugin, extra, deg)) in cases.into_iter().enumerate() {
        let b = load(&smooth(plugin, extra));
        let r = CHI2_DELTA.run(&b, dir(deg, 0.4), UV, 1 + k as u64);
        check_chi2(&format!("{plugin} {extra:.20}, theta_i {deg}"), &r);
    }
}

#[test]
fn roughdielectric_chi2() {
    // (distribution, alpha_u, alpha_v, sample_visible, theta_i, extra parameters)
    let inverted = r#"<float name="int_ior" value="1.0"/> <float name="ext_ior" value="1.5"/>"#;
    let water = r#"<string name="int_ior" value="water"/>"#;
    let configs = [
        ("beckmann", 0.3, 0.3, true, 30.0, TINTS),
        ("beckmann", 0.3, 0.3, true, 160.0, TINTS),
        ("ggx", 0.1, 0.1, true, 70.0, ""),
        ("ggx", 0.2, 0.5, true, 130.0, TINTS),
        ("beckmann", 0.4, 0.4, false, 45.0, ""),
        ("ggx", 0.6, 0.6, false, 100.0, TINTS),
        ("beckmann", 0.5, 0.15, false, 85.0, water),
        ("ggx", 0.25, 0.25, true, 40.0, inverted),
        ("beckmann", 0.2, 0.2, true, 0.0, water),
    ];
    for (k, &(dist, au, av, vis, deg, extra)) in configs.iter().enumerate() {
        let b = load(&rough(dist, au, av, vis, extra));
        let r = CHI2.run(&b, dir(deg, 0.7), UV, 8 + k as u64);
        let name =
            format!("roughdielectric {dist} ({au}, {av}) visible {vis}, theta_i {deg} {extra:.24}");
        check_chi2(&name, &r);
    }
}

#[test]
fn chi2_control_wrong_index_is_rejected() {
    // Samples of eta 1.5 judged against the pdf of eta 1.55, on BsdfChi2's grid.
    let ior = |e: f32| format!(r#"<float name="int_ior" value="{e}"/>"#);
    let a = load(&rough("ggx", 0.3, 0.3, true, &ior(1.5)));
    let b = load(&rough("ggx", 0.3, 0.3, true, &ior(1.55)));
    let wi = dir(40.0, 0.0);
    let cfg = SphereChi2 {
        theta_bins: 20,
        phi_bins: 40,
        samples: 300_000,
    };
    let run = |other: &Bsdf| {
        let mut rng = Pcg32::new(5);
        cfg.run(
            |u| a.sample(wi, rng.next_f32(), u, UV).map(|s| s.wo),
            |w| f64::from(other.pdf(wi, w, UV)),
            99,
        )
    };
    let (right, wrong) = (run(&a), run(&b));
    println!("control: right pdf {right}; wrong pdf {wrong}");
    assert!(right.passes(0.001), "{right}");
    assert!(!wrong.passes(1e-6), "{wrong}");
}

#[test]
fn total_internal_reflection() {
    // BK7 from inside beyond the critical angle (41.7 degrees from the inward normal): only the
    // mirror, with probability 1.
    let b = load(&smooth("dielectric", TINTS));
    let mut rng = Pcg32::new(3);
    for deg in [95.0, 120.0, 135.0] {
        let wi = dir(deg, 1.1);
        for _ in 0..100 {
            let s = b
                .sample(wi, rng.next_f32(), rng.next_vec2(), UV)
                .expect("a sample");
            assert!(s.delta && s.pdf == 1.0 && s.eta == 1.0, "{s:?}");
            assert_eq!(s.wo, Vec3::new(-wi.x, -wi.y, wi.z));
            assert_eq!(s.weight, Vec3::new(0.9, 0.8, 0.7));
        }
    }
    // A slightly rough interface reflects everything back inside at 80 degrees from the inward
    // normal (Beckmann tails never tilt a normal by the 38 degrees refraction would need).
    let r = load(&rough("beckmann", 0.05, 0.05, true, ""));
    let wi = dir(100.0, 0.3);
    let mut n = 0;
    for _ in 0..10_000 {
        if let Some(s) = r.sample(wi, rng.next_f32(), rng.next_vec2(), UV) {
            assert!(s.wo.z < 0.0 && s.eta == 1.0, "{s:?}");
            n += 1;
        }
    }
    assert!(n > 9000, "{n}");
}

/// Mean and standard error of the sampled weight with the radiance scaling undone
/// (`weight * eta^2` for refractions), first channel, white tints.
fn unscaled_albedo(b: &Bsdf, wi: Vec3, n: usize, seed: u64) -> (f64, f64) {
    let mut rng = Pcg32::new(seed);
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        if let Some(x) = b.sample(wi, rng.next_f32(), rng.next_vec2(), UV) {
            let w = f64::from(x.weight.x * x.eta * x.eta);
            s += w;
            s2 += w * w;
        }
    }
    let m = s / n as f64;
    let var = (s2 / n as f64 - m * m).max(0.0) * n as f64 / (n as f64 - 1.0);
    (m, (var / n as f64).sqrt())
}

#[test]
fn energy_is_conserved() {
    let inverted = r#"<float name="int_ior" value="1.0"/> <float name="ext_ior" value="1.5"/>"#;
    for (plugin, extra) in [
        ("dielectric", ""),
        ("dielectric", inverted),
        ("thindielectric", ""),
    ] {
        for deg in [0.0, 40.0, 80.0, 100.0, 140.0, 180.0] {
            let b = load(&smooth(plugin, extra));
            let (m, se) = unscaled_albedo(&b, dir(deg, 0.2), 10_000, 1);
            assert!(
                (m - 1.0).abs() <= 4.0 * se + 1e-6,
                "{plugin} {extra} {deg}: {m} +- {se}"
            );
        }
    }
    for (k, (dist, a, vis, extra)) in [
        ("beckmann", 0.1, true, ""),
        ("ggx", 0.3, false, ""),
        ("beckmann", 0.7, false, inverted),
        ("ggx", 1.0, true, ""),
        ("ggx", 0.5, false, inverted),
    ]
    .into_iter()
    .enumerate()
    {
        for deg in [0.0, 60.0, 85.0, 95.0, 120.0, 180.0] {
            let b = load(&rough(dist, a, a, vis, extra));
            let (m, se) = unscaled_albedo(&b, dir(deg, 0.5), 100_000, 20 + k as u64);
            println!("{dist} alpha {a} visible {vis} {extra:.8} theta_i {deg}: {m:.5} +- {se:.5}");
            // 1e-6: the two eta^2 factors of a refraction cancel only to rounding.
            assert!(
                m - 4.0 * se <= 1.0 + 1e-6,
                "{dist} {a} {vis} {extra} {deg}: {m} +- {se}"
            );
        }
    }
}

/// Largest relative violation of `f(wo, wi) = (eta_o / eta_i)^2 f(wi, wo)` (`f` without
/// cosine; indices of the sides of `wi` and `wo`, equal for reflection) over random pairs; with
/// `plain`, the ordinary reciprocity `f(wo, wi) = f(wi, wo)` instead.
fn reciprocity_error(b: &Bsdf, eta: f32, plain: bool, seed: u64) -> f32 {
    let mut rng = Pcg32::new(seed);
    let (mut worst, mut nonzero) = (0.0f32, [0usize; 2]);
    for _ in 0..40_000 {
        let mut pick = || uniform_direction(rng.next_vec2(), true);
        let (wi, wo) = (pick(), pick());
        if wi.z.abs() < 1e-2 || wo.z.abs() < 1e-2 {
            continue;
        }
        let ratio = if plain || wi.z * wo.z > 0.0 {
            1.0
        } else if wi.z > 0.0 {
            eta * eta
        } else {
            1.0 / (eta * eta)
        };
        let f = b.eval(wi, wo, UV).x / wo.z.abs();
        let g = b.eval(wo, wi, UV).x / wi.z.abs();
        let m = f.abs().max(g.abs());
        // Values near zero (next to total internal reflection, where 1 - F cancels) carry
        // single-precision noise of their own; they are left out.
        if m > 1e-2 {
            nonzero[usize::from(wi.z * wo.z < 0.0)] += 1;
            worst = worst.max((g - ratio * f).abs() / m);
        }
    }
    assert!(
        nonzero.iter().all(|&n| n > 200),
        "too few pairs {nonzero:?}"
    );
    worst
}

#[test]
fn refraction_is_reciprocal_up_to_eta_squared() {
    for (k, (xml, eta)) in [
        (rough("beckmann", 0.4, 0.4, true, ""), 1.5046 / 1.000277),
        (rough("ggx", 0.3, 0.7, false, ""), 1.5046 / 1.000277),
        (
            rough(
                "ggx",
                0.5,
                0.5,
                true,
                r#"<float name="int_ior" value="1.2"/>
                <float name="ext_ior" value="1.5"/>"#,
            ),
            0.8,
        ),
    ]
    .iter()
    .enumerate()
    {
        let e = reciprocity_error(&load(xml), *eta, false, 40 + k as u64);
        println!("generalized reciprocity error {e:.2e}");
        assert!(e < 2e-3, "{e}: {xml}");
    }
    // Control: plain reciprocity does not hold across the interface, and the check sees it.
    let glass = load(&rough("ggx", 0.5, 0.5, true, ""));
    assert!(reciprocity_error(&glass, 1.5, true, 50) > 0.3);
}

#[test]
fn defaults_match_mitsuba() {
    let eta = 1.5046f32 / 1.000277;
    match load(r#"<bsdf type="dielectric"/>"#) {
        Bsdf::Dielectric(d) => assert_eq!(d.eta, eta),
        other => panic!("{other:?}"),
    }
    match load(r#"<bsdf type="thindielectric"/>"#) {
        Bsdf::ThinDielectric(d) => assert_eq!(d.eta, eta),
        other => panic!("{other:?}"),
    }
    match load(r#"<bsdf type="roughdielectric"><string name="int_ior" value="water"/></bsdf>"#) {
        Bsdf::RoughDielectric(d) => {
            // Mitsuba reports eta = 1.33263075 for water over air.
            assert!((d.eta - 1.332_630_8).abs() < 1e-6, "{}", d.eta);
            let md = d.distribution;
            assert_eq!(
                (md.alpha_u, md.alpha_v, md.sample_visible),
                (0.1, 0.1, true)
            );
        }
        other => panic!("{other:?}"),
    }
    // Index-matched smooth interfaces are allowed (Mitsuba too) and pass light straight on.
    let b = load(r#"<bsdf type="dielectric"><float name="int_ior" value="1.000277"/></bsdf>"#);
    let s = b.sample(dir(30.0, 0.0), 0.0, Vec2::ZERO, UV).unwrap();
    assert!(
        (s.wo + dir(30.0, 0.0)).norm() < 1e-6 && s.pdf == 1.0,
        "{s:?}"
    );
}

#[test]
fn bad_parameters_are_located_errors() {
    let (d, rd, td) = ("dielectric", "roughdielectric", "thindielectric");
    // (plugin, properties, where the error points, words it contains)
    #[rustfmt::skip]
    let cases = [
        (d, r#"<float name="int_ior" value="-1.5"/>"#, "int_ior", "positive"),
        (td, r#"<float name="ext_ior" value="0"/>"#, "ext_ior", "positive"),
        (rd, r#"<float name="int_ior" value="0"/>"#, "int_ior", "positive"),
        (d, r#"<string name="int_ior" value="glass"/>"#, "int_ior", "unknown material \"glass\""),
        (rd, r#"<float name="int_ior" value="1.33"/> <float name="ext_ior" value="1.33"/>"#, "int_ior", "must differ"),
        (rd, r#"<float name="alpha" value="-0.2"/>"#, "alpha", "positive"),
        (rd, r#"<string name="distribution" value="blinn"/>"#, "distribution", "blinn"),
        (rd, r#"<float name="alpha_v" value="0.2"/>"#, "alpha_v", "alpha_u"),
        (d, r#"<rgb name="specular_transmittance" value="1.5"/>"#, "specular_transmittance", "[0, 1]"),
        (td, r#"<float name="alpha" value="0.2"/>"#, "alpha", "unused"),
    ];
    for (plugin, props, prop, words) in cases {
        bad(plugin, props, prop, words);
    }
}

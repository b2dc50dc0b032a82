//! `conductor` and `roughconductor`: sampling against the pdf, agreement with Mitsuba 3's
//! samples, reciprocity, energy, and located errors for bad parameters.
//!
//! Every material is built from Mitsuba 3 XML through the loader, so the parameter names and
//! defaults are exercised too. The chi-square tests (listed in [`N_CHI2`]) run at the Šidák
//! level `sidak_alpha(0.01, N_CHI2)` with seeds 1..=N_CHI2; run with `--nocapture` to see the
//! p-values. The eval/pdf values themselves are compared with Mitsuba in `bsdf_mitsuba_eval.rs`
//! (cases `tests/bsdf_cases/conductor*.xml`, `roughconductor*.xml`). Each kind of check has a
//! control that must fail: a 5% wrong roughness for the chi-square test, the wrong metal for the
//! Mitsuba sample table, a refraction for the reciprocity check.

// Reference values are kept as the reference renderer printed them.
#![allow(clippy::excessive_precision)]
use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_lab::stats::{sampled_albedo, Chi2Result, Pcg32, SphereChi2};
use tessera_tests::bsdf::{
    assert_bad_bsdf as bad, assert_chi2_passes, dir_at as dir, load_bsdf_xml as load, rough_xml,
    uniform_direction, CHI2_HALF as CHI2,
};

const UV: Vec2 = Vec2::new(0.25, 0.75);

/// Chi-square tests in this file: 10 rough configurations (the smooth conductor has a single
/// delta direction, which a chi-square cannot test: it is checked sample by sample).
const N_CHI2: usize = 10;

fn check_chi2(name: &str, r: &Chi2Result) {
    assert_chi2_passes(name, r, N_CHI2)
}

fn rough(dist: &str, au: f32, av: f32, visible: bool, extra: &str) -> String {
    rough_xml("roughconductor", dist, au, av, visible, extra)
}

#[test]
fn roughconductor_chi2() {
    // (distribution, alpha_u, alpha_v, sample_visible, theta_i, phi_i)
    let configs = [
        ("beckmann", 0.1, 0.1, true, 30.0, 0.0),
        ("beckmann", 0.1, 0.1, false, 30.0, 0.0),
        ("ggx", 0.1, 0.1, true, 70.0, 0.3),
        ("ggx", 0.5, 0.5, false, 0.0, 0.0),
        ("beckmann", 0.5, 0.5, true, 85.0, 1.0),
        ("ggx", 0.1, 0.4, true, 45.0, 0.7),
        ("beckmann", 0.4, 0.1, false, 60.0, 0.7),
        ("ggx", 0.3, 0.08, false, 85.0, 2.0),
        ("beckmann", 0.08, 0.3, true, 80.0, 0.4),
        ("ggx", 1.0, 1.0, true, 89.0, 0.0),
    ];
    let tint = r#"<string name="material" value="Cu"/>
        <rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/>"#;
    for (k, &(dist, au, av, vis, deg, phi)) in configs.iter().enumerate() {
        let b = load(&rough(dist, au, av, vis, tint));
        let r = CHI2.run(&b, dir(deg, phi), UV, 1 + k as u64);
        let name = format!("roughconductor {dist} ({au}, {av}) visible {vis}, theta_i {deg}");
        check_chi2(&name, &r);
    }
}

#[test]
fn conductor_is_a_mirror() {
    let b = load(&conductor_xml("Cu"));
    let mut rng = Pcg32::new(7);
    for _ in 0..10_000 {
        let u = rng.next_vec2();
        let z = u.x.max(1e-4);
        let r = (1.0 - z * z).sqrt();
        let p = std::f32::consts::TAU * u.y;
        let wi = Vec3::new(r * p.cos(), r * p.sin(), z);
        let s = b
            .sample(wi, rng.next_f32(), rng.next_vec2(), UV)
            .expect("front side samples");
        assert!(s.delta && s.pdf == 1.0 && s.eta == 1.0, "{s:?}");
        assert_eq!(s.wo, Vec3::new(-wi.x, -wi.y, wi.z));
        assert!(s.weight.min_element() > 0.0 && s.weight.max_element() <= 1.0);
        assert_eq!(
            (b.eval(wi, s.wo, UV), b.pdf(wi, s.wo, UV)),
            (Vec3::ZERO, 0.0)
        );
    }
}

#[test]
fn chi2_control_wrong_roughness_is_rejected() {
    // Samples of alpha 0.3 judged against the pdf of alpha 0.315, on BsdfChi2's grid.
    let (a, b) = (
        load(&rough("ggx", 0.3, 0.3, true, "")),
        load(&rough("ggx", 0.315, 0.315, true, "")),
    );
    let wi = dir(40.0, 0.0);
    let cfg = SphereChi2 {
        theta_bins: 20,
        phi_bins: 40,
        samples: 300_000,
    };
    let right = cfg.run(
        |u| a.sample(wi, 0.5, u, UV).map(|s| s.wo),
        |w| f64::from(a.pdf(wi, w, UV)),
        99,
    );
    let wrong = cfg.run(
        |u| a.sample(wi, 0.5, u, UV).map(|s| s.wo),
        |w| f64::from(b.pdf(wi, w, UV)),
        99,
    );
    println!("control: right pdf {right}; wrong pdf {wrong}");
    assert!(right.passes(0.001), "{right}");
    assert!(!wrong.passes(1e-6), "{wrong}");
}

#[test]
fn back_side_scatters_nothing() {
    for xml in [
        r#"<bsdf type="conductor"/>"#.to_string(),
        rough("ggx", 0.3, 0.3, true, ""),
        rough("beckmann", 0.3, 0.1, false, ""),
    ] {
        let b = load(&xml);
        let (wi, wo) = (dir(120.0, 0.3), dir(50.0, 2.0));
        assert!(b.sample(wi, 0.5, Vec2::new(0.3, 0.6), UV).is_none());
        assert_eq!(b.eval(wi, wo, UV), Vec3::ZERO);
        assert_eq!(b.eval(wo, wi, UV), Vec3::ZERO);
        assert_eq!(b.pdf(wi, wo, UV), 0.0);
    }
}

/// Mitsuba 3.9.1 `scalar_rgb` samples of `conductor` (`u1` = 0.5, `u2` = (0.5, 0.5)): wi, wo,
/// weight, pdf (0 = no sample). Made with `b.sample(mi.BSDFContext(), si, 0.5, (0.5, 0.5))`
/// on `si.wi = wi`, `si.sh_frame` = identity.
#[rustfmt::skip]
const MITSUBA_SAMPLES: &[(&str, [f32; 10])] = &[
    ("Au", [0.132813452, 0.111867227, 0.984807753, -0.132813454, -0.111867227, 0.98480773, 0.966675997, 0.802004397, 0.324145079, 1.0]),
    ("Au", [0.662372764, 0.557908883, 0.5, -0.662372768, -0.557908893, 0.5, 0.962210417, 0.804370821, 0.37117517, 1.0]),
    ("Au", [0.761931732, 0.641766244, 0.0871557427, -0.761931717, -0.64176625, 0.0871557444, 0.976087213, 0.928589284, 0.746859074, 1.0]),
    ("Au", [0.585903107, 0.493499379, -0.64278761, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    ("rgb", [0.132813452, 0.111867227, 0.984807753, -0.132813454, -0.111867227, 0.98480773, 0.856752872, 0.492633969, 0.350798905, 1.0]),
    ("rgb", [0.662372764, 0.557908883, 0.5, -0.662372768, -0.557908893, 0.5, 0.851294279, 0.499127835, 0.367288619, 1.0]),
    ("rgb", [0.761931732, 0.641766244, 0.0871557427, -0.761931717, -0.64176625, 0.0871557444, 0.869948506, 0.674842119, 0.565679252, 1.0]),
    ("rgb", [0.0666603889, 0.056147271, -0.996194698, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
];

fn conductor_xml(which: &str) -> String {
    match which {
        "rgb" => r#"<bsdf type="conductor">
            <rgb name="eta" value="0.2, 0.9, 1.1"/> <rgb name="k" value="3.9, 2.4, 2.1"/>
            <rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/></bsdf>"#
            .to_string(),
        name => {
            format!(r#"<bsdf type="conductor"><string name="material" value="{name}"/></bsdf>"#)
        }
    }
}

/// Rows of [`MITSUBA_SAMPLES`] named `which` that `b` disagrees with.
fn sample_mismatches(b: &Bsdf, which: &str) -> Vec<String> {
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * a.abs().max(b.abs()) + 1e-6;
    let mut bad = Vec::new();
    for (_, v) in MITSUBA_SAMPLES.iter().filter(|(n, _)| *n == which) {
        let wi = Vec3::new(v[0], v[1], v[2]);
        let got = b.sample(wi, 0.5, Vec2::splat(0.5), UV);
        let ok = match got {
            None => v[9] == 0.0,
            Some(s) => {
                let want = [v[3], v[4], v[5], v[6], v[7], v[8], v[9]];
                let have = [
                    s.wo.x, s.wo.y, s.wo.z, s.weight.x, s.weight.y, s.weight.z, s.pdf,
                ];
                s.delta && s.eta == 1.0 && want.iter().zip(have).all(|(&w, h)| close(w, h))
            }
        };
        if !ok {
            bad.push(format!("{which}: wi {wi}: {got:?}, Mitsuba {v:?}"));
        }
    }
    bad
}

#[test]
fn conductor_samples_match_mitsuba() {
    for which in ["Au", "rgb"] {
        let bad = sample_mismatches(&load(&conductor_xml(which)), which);
        assert!(bad.is_empty(), "{}", bad.join("\n"));
    }
    // Control: copper is not gold.
    assert!(!sample_mismatches(&load(&conductor_xml("Cu")), "Au").is_empty());
}

/// Largest relative violation of `f(wi, wo) / |cos o| == f(wo, wi) / |cos i|` over random
/// pairs of the upper hemisphere (or both hemispheres with `both_sides`).
fn reciprocity_error(b: &Bsdf, seed: u64, both_sides: bool) -> f32 {
    let mut rng = Pcg32::new(seed);
    let mut worst = 0.0f32;
    let mut nonzero = 0;
    for _ in 0..20_000 {
        let mut pick = || uniform_direction(rng.next_vec2(), both_sides);
        let (wi, wo) = (pick(), pick());
        if wi.z.abs() < 1e-3 || wo.z.abs() < 1e-3 {
            continue;
        }
        let a = b.eval(wi, wo, UV) / wo.z.abs();
        let c = b.eval(wo, wi, UV) / wi.z.abs();
        for ch in 0..3 {
            let m = a[ch].abs().max(c[ch].abs());
            if m > 1e-4 {
                nonzero += 1;
                worst = worst.max((a[ch] - c[ch]).abs() / m);
            }
        }
    }
    assert!(nonzero > 1000, "too few nonzero pairs ({nonzero})");
    worst
}

#[test]
fn roughconductor_is_reciprocal() {
    let tint = r#"<string name="material" value="Au"/>"#;
    for (k, xml) in [
        rough("beckmann", 0.3, 0.3, true, tint),
        rough("ggx", 0.2, 0.6, false, tint),
        rough("beckmann", 0.7, 0.25, true, ""),
    ]
    .iter()
    .enumerate()
    {
        let e = reciprocity_error(&load(xml), 10 + k as u64, false);
        println!("reciprocity error {e:.2e}: {xml}");
        assert!(e < 1e-4, "{e}: {xml}");
    }
    // Control: refraction with radiance scaling is not reciprocal, and the check sees it.
    let glass = load(r#"<bsdf type="roughdielectric"><float name="alpha" value="0.4"/></bsdf>"#);
    assert!(reciprocity_error(&glass, 20, true) > 0.1);
}

#[test]
fn white_furnace_albedo_at_most_one() {
    // A perfect mirror reflects everything.
    let mirror = load(r#"<bsdf type="conductor"/>"#);
    for deg in [0.0, 45.0, 89.0] {
        let (m, se) = sampled_albedo(&mirror, dir(deg, 0.2), UV, 1000, 1);
        assert_eq!((m, se), (Vec3::ONE, Vec3::ZERO), "theta_i {deg}");
    }
    // Rough perfect reflectors lose the light that single scattering shadows, never gain.
    for (k, (dist, a, vis)) in [
        ("beckmann", 0.1, true),
        ("ggx", 0.1, false),
        ("beckmann", 0.6, false),
        ("ggx", 1.0, true),
        ("ggx", 1.0, false),
    ]
    .into_iter()
    .enumerate()
    {
        for deg in [0.0, 60.0, 85.0] {
            let b = load(&rough(dist, a, a, vis, ""));
            let (m, se) = sampled_albedo(&b, dir(deg, 0.5), UV, 200_000, 30 + k as u64);
            println!(
                "{dist} alpha {a} visible {vis} theta_i {deg}: albedo {} +- {}",
                m.x, se.x
            );
            assert!(
                m.x - 4.0 * se.x <= 1.0,
                "{dist} {a} {vis} {deg}: {m} +- {se}"
            );
        }
    }
}

#[test]
fn defaults_and_spellings_match_mitsuba() {
    let d = load(r#"<bsdf type="roughconductor"/>"#);
    let Bsdf::RoughConductor(d) = d else {
        panic!("not a roughconductor")
    };
    let md = d.distribution;
    assert_eq!(
        md.kind,
        tessera_core::bsdf::microfacet::MicrofacetKind::Beckmann
    );
    assert_eq!(
        (md.alpha_u, md.alpha_v, md.sample_visible),
        (0.1, 0.1, true)
    );
    assert_eq!((d.eta.eval(UV), d.k.eval(UV)), (Vec3::ZERO, Vec3::ONE));
    let g = load(r#"<bsdf type="roughconductor"><string name="distribution" value="GGX"/></bsdf>"#);
    let Bsdf::RoughConductor(g) = g else {
        panic!("not a roughconductor")
    };
    assert_eq!(
        g.distribution.kind,
        tessera_core::bsdf::microfacet::MicrofacetKind::Ggx
    );
    // `eta` alone keeps k = 1; `material none` with eta/k is allowed.
    load(r#"<bsdf type="conductor"><float name="eta" value="2"/></bsdf>"#);
    load(
        r#"<bsdf type="conductor"><string name="material" value="none"/><float name="k" value="2"/></bsdf>"#,
    );
    for name in ["Ag", "Al", "Cu", "Cr", "a-C", "TiO2-e_palik", "W"] {
        load(&conductor_xml(name));
    }
}

#[test]
fn bad_parameters_are_located_errors() {
    let (c, rc) = ("conductor", "roughconductor");
    let au = r#"<string name="material" value="Au"/>"#;
    let (au_eta, au_k) = (
        format!(r#"{au} <float name="eta" value="2"/>"#),
        format!(r#"{au} <float name="k" value="2"/>"#),
    );
    // (plugin, properties, where the error points, words it contains)
    #[rustfmt::skip]
    let cases = [
        (rc, r#"<float name="alpha" value="-0.1"/>"#, "alpha", "positive"),
        (rc, r#"<float name="alpha_u" value="0.1"/> <float name="alpha_v" value="0"/>"#, "alpha_v", "positive"),
        (rc, r#"<float name="alpha_u" value="0.1"/>"#, "alpha_u", "alpha_v"),
        (rc, r#"<float name="alpha" value="0.1"/>
        <float name="alpha_u" value="0.1"/> <float name="alpha_v" value="0.2"/>"#, "alpha", "not both"),
        (rc, r#"<string name="distribution" value="phong"/>"#, "distribution", "phong"),
        (c, r#"<string name="material" value="Unobtainium"/>"#, "material", "unknown conductor \"Unobtainium\""),
        // Names are case-sensitive, as Mitsuba's file lookup is.
        (rc, r#"<string name="material" value="au"/>"#, "material", "unknown conductor"),
        (c, &au_eta, "material", "not both"),
        (c, &au_k, "k", "unused"),
        (c, r#"<float name="eta" value="-1"/>"#, "eta", "non-negative"),
        (rc, r#"<boolean name="sample_visible" value="maybe"/>"#, r#"value="maybe""#, "maybe"),
    ];
    for (plugin, props, prop, words) in cases {
        bad(plugin, props, prop, words);
    }
}

/// `material` `none` (eta 0, k 1) skips the Fresnel formula and uses 1: exact, because the
/// formula gives exactly 1 there. Checked on a million cosines spread over `[0, 1]` by their bit
/// patterns (every float in `[0, 1]` was checked once by hand). Control: a metal whose `eta` is
/// barely above 0 does not give exactly 1, so the comparison can fail.
#[test]
fn perfect_reflector_fresnel_is_exactly_one() {
    use tessera_core::bsdf::fresnel::fresnel_conductor;
    use tessera_core::Color;
    let one_bits = 1.0f32.to_bits();
    let cosines = (0..=1_000_000u32)
        .map(|i| f32::from_bits((u64::from(one_bits) * u64::from(i) / 1_000_000) as u32));
    let mut not_one = 0;
    let mut control_not_one = 0;
    for c in cosines {
        if fresnel_conductor(c, Color::ZERO, Color::ONE) != Color::ONE {
            not_one += 1;
        }
        if fresnel_conductor(c, Color::splat(1e-3), Color::ONE) != Color::ONE {
            control_not_one += 1;
        }
    }
    assert_eq!(not_one, 0);
    assert!(control_not_one > 100_000, "{control_not_one}");
}

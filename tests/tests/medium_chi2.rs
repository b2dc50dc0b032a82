//! Sampling in participating media against its densities: the phase functions (`isotropic`,
//! `hg` for g in {-0.9, -0.5, 0, 0.3, 0.9}) by chi-square on the sphere, their normalisation by
//! quadrature, and free-flight distances through a medium whose extinction differs per channel
//! (chi-square of the distances against the channel mixture, and Student t-tests of the weighted
//! estimates against Beer-Lambert's closed forms).
//!
//! Each chi-square uses its own seed and the Šidák-corrected level for the [`N_TESTS`] tests of
//! the file; each test has a control (the same samples against a wrong density or closed form)
//! that must be rejected.
use glam::Vec3;
use tessera_core::math::Norm;
use tessera_core::medium::{
    sample_free_flight, ChannelRatios, HenyeyGreenstein, Isotropic, PhaseFunction,
};
use tessera_core::Color;
use tessera_lab::stats::{
    chi2_test, sidak_alpha, t_test_mean, Chi2Result, Moments, Pcg32, SphereChi2,
    DEFAULT_MIN_EXPECTED,
};
use tessera_tests::bsdf::assert_chi2_passes;
use tessera_tests::phase::sphere_integral;

/// Chi-square tests in this file: 1 isotropic, 2-6 hg, 7 free-flight distances.
const N_TESTS: usize = 7;

/// A direction toward the previous vertex that is not along an axis, so that the forward peak of
/// a strongly anisotropic function falls inside the grid rather than on its pole.
fn wi() -> Vec3 {
    Vec3::new(-0.6, 0.3, -0.2).unit()
}

fn phase_chi2(phase: PhaseFunction, claimed: PhaseFunction, seed: u64) -> Chi2Result {
    let wi = wi();
    SphereChi2 {
        theta_bins: 40,
        phi_bins: 80,
        samples: 1_000_000,
    }
    .run(
        |u| Some(phase.sample(wi, u).wo),
        |wo| f64::from(claimed.eval(wi, wo)),
        seed,
    )
}

fn hg(g: f32) -> PhaseFunction {
    PhaseFunction::Hg(HenyeyGreenstein { g })
}

#[test]
fn t01_isotropic() {
    let iso = PhaseFunction::Isotropic(Isotropic);
    assert_chi2_passes(
        "isotropic",
        &phase_chi2(iso.clone(), iso.clone(), 1),
        N_TESTS,
    );
    // Control: isotropic samples are not those of hg with g = 0.1.
    let control = phase_chi2(iso, hg(0.1), 1);
    println!("control isotropic vs hg 0.1: {control}");
    assert!(!control.passes(1e-6), "control passed: {control}");
}

fn hg_case(g: f32, wrong_g: f32, seed: u64) {
    let r = phase_chi2(hg(g), hg(g), seed);
    assert_chi2_passes(&format!("hg g = {g}"), &r, N_TESTS);
    let control = phase_chi2(hg(g), hg(wrong_g), seed);
    println!("control hg g = {g} against g = {wrong_g}: {control}");
    assert!(!control.passes(1e-6), "control passed: {control}");
    // Each sample reports the density the evaluation gives for its direction.
    let mut rng = Pcg32::new(seed + 100);
    for _ in 0..10_000 {
        let s = hg(g).sample(wi(), rng.next_vec2());
        let e = hg(g).eval(wi(), s.wo);
        assert!((s.pdf - e).abs() <= 1e-4 * e.max(1.0), "{} vs {}", s.pdf, e);
        assert!((s.wo.norm() - 1.0).abs() < 1e-5);
    }
}

#[test]
fn t02_hg_minus_0_9() {
    hg_case(-0.9, -0.85, 2);
}
#[test]
fn t03_hg_minus_0_5() {
    hg_case(-0.5, -0.45, 3);
}
#[test]
fn t04_hg_0() {
    hg_case(0.0, 0.05, 4);
}
#[test]
fn t05_hg_0_3() {
    hg_case(0.3, 0.35, 5);
}
#[test]
fn t06_hg_0_9() {
    hg_case(0.9, 0.85, 6);
}

/// `∫ p dω`, many cosines about the direction of travel and a few azimuths.
fn integral(p: PhaseFunction) -> f64 {
    sphere_integral(&p, Vec3::new(0.0, 0.0, -1.0), 200_000, 8)
}

#[test]
fn phase_functions_integrate_to_one() {
    let all = [
        PhaseFunction::Isotropic(Isotropic),
        hg(-0.9),
        hg(-0.5),
        hg(0.0),
        hg(0.3),
        hg(0.9),
    ];
    for p in all {
        let i = integral(p.clone());
        println!("{p:?}: integral {i:.6}");
        assert!((i - 1.0).abs() < 1e-3, "{p:?} integrates to {i}");
    }
    // Control: the quadrature sees a wrong normalisation (hg's numerator without 1 - g^2).
    let wrong = integral(hg(0.5)) / (1.0 - 0.25);
    assert!((wrong - 1.0).abs() > 0.1, "control passed: {wrong}");
}

const SIGMA_T: Color = Color::new(0.5, 1.0, 3.0);
const ALBEDO: Color = Color::new(0.9, 0.5, 0.2);
const T_MAX: f32 = 1.5;
const BINS: usize = 30;

/// Chi-square of sampled distances in `[0, T_MAX)` (BINS bins) plus the pass, against the
/// mixture of the three channels' exponentials with extinction `claimed`.
fn distances_chi2(claimed: Color, seed: u64) -> Chi2Result {
    let mut rng = Pcg32::new(seed);
    let n = 1_000_000;
    let mut observed = vec![0.0; BINS + 1];
    for _ in 0..n {
        let (uc, u) = (rng.next_f32(), rng.next_f32());
        let channel = ChannelRatios::new(uc).channel;
        let ff = sample_free_flight(SIGMA_T, SIGMA_T * ALBEDO, T_MAX, channel, u);
        let cell = if ff.scattered {
            assert!(ff.t >= 0.0 && ff.t < T_MAX, "{}", ff.t);
            ((ff.t / T_MAX * BINS as f32) as usize).min(BINS - 1)
        } else {
            assert_eq!(ff.t, T_MAX);
            BINS
        };
        observed[cell] += 1.0;
    }
    let cdf = |t: f64| -> f64 {
        (0..3)
            .map(|k| 1.0 - (-f64::from(claimed[k]) * t).exp())
            .sum::<f64>()
            / 3.0
    };
    let mut expected: Vec<f64> = (0..BINS)
        .map(|i| {
            let a = f64::from(T_MAX) * i as f64 / BINS as f64;
            let b = f64::from(T_MAX) * (i + 1) as f64 / BINS as f64;
            (cdf(b) - cdf(a)) * n as f64
        })
        .collect();
    expected.push((1.0 - cdf(f64::from(T_MAX))) * n as f64);
    chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED)
}

#[test]
fn t07_free_flight_distances() {
    assert_chi2_passes("free flight", &distances_chi2(SIGMA_T, 7), N_TESTS);
    let control = distances_chi2(SIGMA_T * 1.05, 7);
    println!("control sigma_t 5% high: {control}");
    assert!(!control.passes(1e-6), "control passed: {control}");
}

/// Estimates, per channel, the light that passes the segment (`exp(-sigma_t T_MAX)`) and the
/// light scattered in `[0.2, 0.7)` (`albedo (exp(-0.2 sigma_t) - exp(-0.7 sigma_t))`) from the
/// samples' weights, and t-tests them against `sigma_t` = `claimed`.
fn weights_t_tests(claimed: Color) -> Vec<(String, f64)> {
    let mut rng = Pcg32::new(99);
    let mut pass = [Moments::new(), Moments::new(), Moments::new()];
    let mut band = [Moments::new(), Moments::new(), Moments::new()];
    for _ in 0..1_000_000 {
        let (uc, u) = (rng.next_f32(), rng.next_f32());
        let channel = ChannelRatios::new(uc).channel;
        let ff = sample_free_flight(SIGMA_T, SIGMA_T * ALBEDO, T_MAX, channel, u);
        let w = ff.mixture_weight();
        let in_band = ff.scattered && ff.t >= 0.2 && ff.t < 0.7;
        for k in 0..3 {
            pass[k].push(if ff.scattered { 0.0 } else { f64::from(w[k]) });
            band[k].push(if in_band { f64::from(w[k]) } else { 0.0 });
        }
    }
    let mut out = Vec::new();
    for k in 0..3 {
        let s = f64::from(claimed[k]);
        let a = f64::from(ALBEDO[k]);
        let r = t_test_mean(&pass[k], (-s * f64::from(T_MAX)).exp());
        out.push((format!("pass, channel {k}: {r}"), r.p_value));
        let r = t_test_mean(&band[k], a * ((-0.2 * s).exp() - (-0.7 * s).exp()));
        out.push((format!("band, channel {k}: {r}"), r.p_value));
    }
    out
}

#[test]
fn free_flight_weights_match_beer_lambert() {
    let alpha = sidak_alpha(0.01, 6);
    for (what, p) in weights_t_tests(SIGMA_T) {
        println!("{what}");
        assert!(p >= alpha, "{what}");
    }
    // Control: the same estimates against sigma_t 5% high; every pass estimate must be
    // rejected (the band's closed form moves less for the densest channel).
    let control = weights_t_tests(SIGMA_T * 1.05);
    for (what, p) in control.iter().step_by(2) {
        println!("control {what}");
        assert!(*p < 1e-6, "control passed: {what}");
    }
}

#[test]
fn grey_extinction_weights_are_albedo_and_one() {
    let s = Color::splat(2.0);
    let a = Color::new(0.3, 0.6, 0.9);
    for i in 0..100 {
        let u = (i as f32 + 0.5) / 100.0;
        let ff = sample_free_flight(s, s * a, 1.0, 1, u);
        let want = if ff.scattered { a } else { Color::ONE };
        let mut ratios = ChannelRatios::new(0.4);
        let w = ratios.record(&ff);
        assert!((w - want).abs().max_element() < 1e-5, "{ff:?}");
        assert!(
            (ff.mixture_weight() - want).abs().max_element() < 1e-5,
            "{ff:?}"
        );
        assert_eq!(ratios.weight(), 1.0);
    }
}

/// Two segments in a row, the way a path meets them (the channel chosen once, the ratios kept
/// along the path): the estimate of "pass a segment of length 0.8, then collide within
/// [0.2, 0.7) of the next" for channel j, `exp(-0.8 sigma_j) albedo_j (exp(-0.2 sigma_j) -
/// exp(-0.7 sigma_j))`, t-tested per channel, with the control against sigma_t 5% high.
fn path_t_tests(claimed: Color) -> Vec<(String, f64)> {
    let mut rng = Pcg32::new(1234);
    let mut m = [Moments::new(), Moments::new(), Moments::new()];
    for _ in 0..1_000_000 {
        let mut ratios = ChannelRatios::new(rng.next_f32());
        let first = sample_free_flight(
            SIGMA_T,
            SIGMA_T * ALBEDO,
            0.8,
            ratios.channel,
            rng.next_f32(),
        );
        let mut throughput = ratios.record(&first);
        let mut hit = !first.scattered;
        if hit {
            let second = sample_free_flight(
                SIGMA_T,
                SIGMA_T * ALBEDO,
                10.0,
                ratios.channel,
                rng.next_f32(),
            );
            throughput *= ratios.record(&second);
            hit = second.scattered && second.t >= 0.2 && second.t < 0.7;
        }
        let w = throughput * ratios.weight();
        for k in 0..3 {
            m[k].push(if hit { f64::from(w[k]) } else { 0.0 });
            assert!(
                !hit || w[k] <= 3.0 * ALBEDO[k] + 1e-5,
                "weight {w} above its bound"
            );
        }
    }
    (0..3)
        .map(|k| {
            let s = f64::from(claimed[k]);
            let want =
                (-0.8 * s).exp() * f64::from(ALBEDO[k]) * ((-0.2 * s).exp() - (-0.7 * s).exp());
            let r = t_test_mean(&m[k], want);
            (format!("two segments, channel {k}: {r}"), r.p_value)
        })
        .collect()
}

#[test]
fn channel_ratios_along_a_path_match_beer_lambert() {
    let alpha = sidak_alpha(0.01, 3);
    for (what, p) in path_t_tests(SIGMA_T) {
        println!("{what}");
        assert!(p >= alpha, "{what}");
    }
    let control = path_t_tests(SIGMA_T * 1.05);
    let worst = control.iter().map(|c| c.1).fold(1.0, f64::min);
    for (what, _) in &control {
        println!("control {what}");
    }
    assert!(worst < 1e-6, "control passed: {control:?}");
}

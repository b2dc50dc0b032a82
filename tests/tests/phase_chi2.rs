//! Sampling of the phase functions `rayleigh`, `tabphase` and `blendphase` against their
//! densities (chi-square on the sphere), their normalisation by quadrature, and what each
//! sample reports (its density equal to the function's, its weight 1 for these exactly sampled
//! kinds). The functions are built from scene text by the loader.
//!
//! Each chi-square uses its own seed and the Šidák-corrected level for the [`N_TESTS`] tests of
//! the file; each has a control (the same samples against a slightly different function) that
//! must be rejected.
use glam::Vec3;
use tessera_core::math::Norm;
use tessera_core::medium::PhaseFunction;
use tessera_lab::stats::{Chi2Result, Pcg32, SphereChi2};
use tessera_tests::bsdf::assert_chi2_passes;
use tessera_tests::phase::phase_from_xml;

/// Chi-square tests in this file.
const N_TESTS: usize = 6;

const RAYLEIGH: &str = r#"<phase type="rayleigh"/>"#;
const TAB_SMOOTH: &str =
    r#"<phase type="tabphase"><string name="values" value="0.5, 1.0, 1.5"/></phase>"#;
/// A sharp forward peak (the last interval holds most of the mass), an empty band and a small
/// backward lobe.
const TAB_PEAKED: &str = r#"<phase type="tabphase">
    <string name="values" value="0.3, 0.1 0, 0, 0, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 20, 120"/>
    </phase>"#;
fn blend_hg(weight: f32) -> String {
    format!(
        r#"<phase type="blendphase"><float name="weight" value="{weight}"/>
        <phase type="hg"><float name="g" value="0.9"/></phase>
        <phase type="hg"><float name="g" value="-0.5"/></phase></phase>"#
    )
}

fn wi() -> Vec3 {
    Vec3::new(-0.6, 0.3, -0.2).unit()
}

fn phase_chi2(phase: &PhaseFunction, claimed: &PhaseFunction, seed: u64) -> Chi2Result {
    let wi = wi();
    SphereChi2 {
        theta_bins: 40,
        phi_bins: 80,
        samples: 1_000_000,
    }
    .run(
        |u| Some(phase.sample(wi, u).wo),
        |wo| f64::from(claimed.pdf(wi, wo)),
        seed,
    )
}

/// The chi-square of `xml`'s samples against its density passes; against `control`'s it fails;
/// and each sample's density and weight are what the function says.
fn case(name: &str, xml: &str, control: &str, seed: u64) {
    let p = phase_from_xml(xml);
    assert_chi2_passes(name, &phase_chi2(&p, &p, seed), N_TESTS);
    let c = phase_from_xml(control);
    let r = phase_chi2(&p, &c, seed);
    println!("control {name}: {r}");
    assert!(!r.passes(1e-6), "control passed: {r}");
    let mut rng = Pcg32::new(seed + 100);
    for _ in 0..20_000 {
        let s = p.sample(wi(), rng.next_vec2());
        let (e, d) = (p.eval(wi(), s.wo), p.pdf(wi(), s.wo));
        assert!(
            (s.pdf - d).abs() <= 1e-4 * d.max(1.0),
            "pdf {} vs {d}",
            s.pdf
        );
        assert!(
            (s.weight - e / d).abs() < 1e-4,
            "weight {} vs {}",
            s.weight,
            e / d
        );
        assert!((s.weight - 1.0).abs() < 1e-4, "weight {}", s.weight);
        assert!((s.wo.norm() - 1.0).abs() < 1e-5);
    }
}

#[test]
fn t01_rayleigh() {
    case("rayleigh", RAYLEIGH, r#"<phase type="isotropic"/>"#, 11);
}

#[test]
fn t02_tabphase_smooth() {
    let control = r#"<phase type="tabphase"><string name="values" value="0.5, 1.0, 1.6"/></phase>"#;
    case("tabphase 0.5 1 1.5", TAB_SMOOTH, control, 12);
}

#[test]
fn t03_tabphase_peaked() {
    let control = TAB_PEAKED.replace(", 120", ", 110");
    case("tabphase peaked", TAB_PEAKED, &control, 13);
}

#[test]
fn t04_blendphase_hg() {
    case(
        "blendphase hg 0.9 / -0.5",
        &blend_hg(0.3),
        &blend_hg(0.35),
        14,
    );
}

#[test]
fn t05_blendphase_extremes() {
    // Weight 0 and 1 are one function alone.
    let hg = |g: f32| format!(r#"<phase type="hg"><float name="g" value="{g}"/></phase>"#);
    assert_chi2_passes(
        "blendphase weight 0",
        &phase_chi2(
            &phase_from_xml(&blend_hg(0.0)),
            &phase_from_xml(&hg(0.9)),
            15,
        ),
        N_TESTS,
    );
    let r = phase_chi2(
        &phase_from_xml(&blend_hg(1.0)),
        &phase_from_xml(&hg(-0.5)),
        16,
    );
    assert_chi2_passes("blendphase weight 1", &r, N_TESTS);
    let control = phase_chi2(
        &phase_from_xml(&blend_hg(1.0)),
        &phase_from_xml(&hg(0.9)),
        16,
    );
    assert!(!control.passes(1e-6), "control passed: {control}");
}

#[test]
fn t06_blendphase_nested() {
    let nested = |w: f32| {
        format!(
            r#"<phase type="blendphase"><float name="weight" value="{w}"/><phase type="rayleigh"/>
            <phase type="blendphase"><float name="weight" value="0.25"/>
            <phase type="tabphase"><string name="values" value="1, 0.2, 3"/></phase>
            <phase type="isotropic"/></phase></phase>"#
        )
    };
    case("blendphase nested", &nested(0.6), &nested(0.75), 17);
}

/// `∫ p dω` by the midpoint rule in the cosine about the propagation direction (split at the
/// table's nodes by the fine grid) and the azimuth.
fn integral(p: &PhaseFunction) -> f64 {
    let wi = Vec3::new(0.0, 0.0, -1.0); // propagation along +z: cos = z
    let (nz, nphi) = (280_000, 4);
    let mut sum = 0.0;
    for i in 0..nz {
        let z = -1.0 + (i as f64 + 0.5) * 2.0 / nz as f64;
        let s = (1.0 - z * z).sqrt();
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) * std::f64::consts::TAU / nphi as f64;
            let wo = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
            sum += f64::from(p.eval(wi, wo));
        }
    }
    sum * (2.0 / nz as f64) * (std::f64::consts::TAU / nphi as f64)
}

#[test]
fn phase_functions_integrate_to_one() {
    for xml in [RAYLEIGH, TAB_SMOOTH, TAB_PEAKED, &blend_hg(0.3)] {
        let p = phase_from_xml(xml);
        let i = integral(&p);
        println!("{xml}: integral {i:.6}");
        assert!((i - 1.0).abs() < 1e-3, "{xml} integrates to {i}");
    }
    // Control: a table normalised by the plain sum of its values (not its integral) is seen.
    let values = [0.5f64, 1.0, 1.5];
    let trapezoid = (0.5 * (0.5 + 1.0) + 0.5 * (1.0 + 1.5)) * 1.0;
    let wrong = integral(&phase_from_xml(TAB_SMOOTH)) * trapezoid / values.iter().sum::<f64>();
    assert!((wrong - 1.0).abs() > 0.1, "control passed: {wrong}");
}

/// Rayleigh's closed forms: `3 (1 + c^2) / (16 pi)`, symmetric forward and backward.
#[test]
fn rayleigh_closed_form() {
    let p = phase_from_xml(RAYLEIGH);
    let wi = Vec3::new(0.0, 0.0, -1.0);
    for c in [-1.0f32, -0.5, 0.0, 0.3, 1.0] {
        let wo = Vec3::new((1.0 - c * c).max(0.0).sqrt(), 0.0, c);
        let want = 3.0 * (1.0 + c * c) / (16.0 * std::f32::consts::PI);
        assert!((p.eval(wi, wo) - want).abs() < 1e-6, "c = {c}");
    }
}

//! Sampling of the phase functions `rayleigh`, `tabphase`, `blendphase` and `sggx` against their
//! densities (chi-square on the sphere), their normalisation by quadrature, and what each
//! sample reports (its density equal to the function's, its weight 1 for these exactly sampled
//! kinds). The functions are built from scene text by the loader.
//!
//! Each chi-square uses its own seed and the Šidák-corrected level for the [`N_TESTS`] tests of
//! the file; each has a control (the same samples against a slightly different function) that
//! must be rejected.
use glam::Vec3;
use tessera_core::math::Norm;
use tessera_core::medium::{PhaseFunction, Sggx, SggxMatrix};
use tessera_lab::stats::{Chi2Result, Pcg32, SphereChi2};
use tessera_tests::bsdf::assert_chi2_passes;
use tessera_tests::phase::{phase_from_xml, sphere_integral};

/// Chi-square tests in this file.
const N_TESTS: usize = 9;

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
    case_of(name, &phase_from_xml(xml), &phase_from_xml(control), seed);
}

/// [`case`] for functions already built.
fn case_of(name: &str, p: &PhaseFunction, c: &PhaseFunction, seed: u64) {
    assert_chi2_passes(name, &phase_chi2(p, p, seed), N_TESTS);
    let r = phase_chi2(p, c, seed);
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

fn sggx(c: [f32; 6]) -> PhaseFunction {
    PhaseFunction::Sggx(Sggx {
        s: SggxMatrix::from_channels(c),
    })
}

/// The skewed matrix of Mitsuba 3's own SGGX chi-square test.
const SKEWED: [f32; 6] = [1.0, 0.35, 0.32, 0.52, 0.44, 0.2];

#[test]
fn t07_sggx_skewed() {
    let mut control = SKEWED;
    control[3] = 0.48;
    case_of("sggx skewed", &sggx(SKEWED), &sggx(control), 18);
}

#[test]
fn t08_sggx_fibre_and_sheet() {
    // A thin fibre along y (S_yy small) and a sheet facing y (S_yy large), each seen obliquely.
    let fibre = [1.0, 0.01, 1.0, 0.0, 0.0, 0.0];
    case_of(
        "sggx fibre",
        &sggx(fibre),
        &sggx([1.0, 0.012, 1.0, 0.0, 0.0, 0.0]),
        19,
    );
    let sheet = [0.04, 1.0, 0.04, 0.0, 0.0, 0.0];
    case_of(
        "sggx sheet",
        &sggx(sheet),
        &sggx([0.04, 1.0, 0.05, 0.0, 0.0, 0.0]),
        20,
    );
}

/// The loader reads a one-voxel grid into the fixed function of its matrix.
#[test]
fn t09_sggx_from_a_grid_file() {
    let vol = tessera_tests::scenes_dir().join("media/flakes_uniform.vol");
    let xml = format!(
        r#"<phase type="sggx"><volume type="gridvolume" name="S">
        <string name="filename" value="{}"/></volume></phase>"#,
        vol.display()
    );
    let p = phase_from_xml(&xml);
    assert!(matches!(p, PhaseFunction::Sggx(_)), "{p:?}");
    case_of("sggx from flakes_uniform.vol", &p, &sggx(SKEWED), 21);
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

/// `∫ p dω`, many cosines about the direction of travel (split at the table's nodes by the fine
/// grid) and a few azimuths.
fn integral(p: &PhaseFunction) -> f64 {
    sphere_integral(p, Vec3::new(0.0, 0.0, -1.0), 280_000, 4)
}

#[test]
fn phase_functions_integrate_to_one() {
    for xml in [RAYLEIGH, TAB_SMOOTH, TAB_PEAKED, &blend_hg(0.3)] {
        let p = phase_from_xml(xml);
        let i = integral(&p);
        println!("{xml}: integral {i:.6}");
        assert!((i - 1.0).abs() < 1e-3, "{xml} integrates to {i}");
    }
    // SGGX is not symmetric about the incident direction: a full grid over the sphere, for
    // several incident directions.
    for wi in [wi(), Vec3::Y, Vec3::new(0.8, -0.1, 0.59).unit()] {
        let i = sphere_integral(&sggx(SKEWED), wi, 2000, 2000);
        println!("sggx, wi {wi}: integral {i:.6}");
        assert!((i - 1.0).abs() < 2e-3, "sggx integrates to {i}");
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

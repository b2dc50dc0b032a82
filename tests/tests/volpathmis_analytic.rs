//! `volpathmis` against the closed forms of `media_analytic.rs` (the same scenes, the integrator
//! swapped): Beer-Lambert through an absorbing slab with a different extinction per channel,
//! seen against the sky and on a shadow ray toward a directional light, and white furnaces
//! (every pixel 1) with chromatic extinction, where the joint weights over channels and
//! strategies matter, with and without spectral MIS, and with the blend and tabulated phase
//! functions. One pixel's samples, Student's t-test, significance 0.01 Sidak-corrected over the
//! file; each case has a control (a reference 1% off, or 5% more extinction) that must fail.
use crate::media_analytic::{beer, furnace, slab_against_the_sky, slab_on_a_shadow_ray, THICKNESS};
use tessera_tests::pixel_ttest::{check_pixel, control_pixel as control};

/// t-tests in this file: 2 slabs + 4 furnaces, 3 channels each.
const N_TESTS: usize = 6 * 3;

/// `xml` with `volpathmis` (with `extra` parameters) instead of `volpath`.
fn mis(xml: &str, extra: &str) -> String {
    let from = r#"<integrator type="volpath"/>"#;
    assert!(xml.contains(from));
    xml.replace(
        from,
        &format!(r#"<integrator type="volpathmis">{extra}</integrator>"#),
    )
}

#[test]
fn absorbing_slab_against_the_sky() {
    let xml = mis(&slab_against_the_sky(), "");
    check_pixel("slab, sky", &xml, 40_000, beer(1.0, THICKNESS), N_TESTS);
    control(
        "slab, sky, sigma_t 5% high",
        &xml,
        40_000,
        beer(1.05, THICKNESS),
    );
}

#[test]
fn absorbing_slab_on_a_shadow_ray() {
    let xml = mis(&slab_on_a_shadow_ray(), "");
    let expected = beer(1.0, THICKNESS).map(|t| t / std::f64::consts::PI);
    check_pixel("slab, shadow ray", &xml, 20_000, expected, N_TESTS);
    let wrong = beer(1.05, THICKNESS).map(|t| t / std::f64::consts::PI);
    control("slab, shadow ray, sigma_t 5% high", &xml, 20_000, wrong);
}

fn furnace_case(label: &str, xml: &str) {
    check_pixel(label, xml, 200_000, [1.0; 3], N_TESTS);
    control(&format!("{label} against 0.99"), xml, 200_000, [0.99; 3]);
}

const CHROMATIC: &str =
    r#"<rgb name="sigma_t" value="0.25, 0.5, 1.0"/><float name="scale" value="3"/>"#;

/// Mildly chromatic: without spectral MIS the weights grow with the channels' differences.
const MILD: &str = r#"<rgb name="sigma_t" value="0.8, 0.9, 1.0"/><float name="scale" value="2"/>"#;

#[test]
fn white_furnace_chromatic_extinction() {
    let xml = furnace(
        CHROMATIC,
        r#"<phase type="hg"><float name="g" value="0.7"/></phase>"#,
        false,
    );
    furnace_case("volpathmis furnace, chromatic, hg 0.7", &mis(&xml, ""));
}

#[test]
fn white_furnace_without_spectral_mis() {
    let xml = furnace(MILD, r#"<phase type="rayleigh"/>"#, false);
    let extra = r#"<boolean name="use_spectral_mis" value="false"/>"#;
    furnace_case(
        "volpathmis furnace, no spectral MIS, rayleigh",
        &mis(&xml, extra),
    );
}

#[test]
fn white_furnace_blendphase() {
    let phase = r#"<phase type="blendphase"><float name="weight" value="0.3"/>
      <phase type="hg"><float name="g" value="0.9"/></phase>
      <phase type="hg"><float name="g" value="-0.5"/></phase></phase>"#;
    let xml = furnace(CHROMATIC, phase, false);
    furnace_case("volpathmis furnace, blendphase", &mis(&xml, ""));
}

#[test]
fn white_furnace_tabphase_camera_inside() {
    let phase =
        r#"<phase type="tabphase"><string name="values" value="0.3, 0.1, 0, 0.5, 2, 9"/></phase>"#;
    let xml = furnace(CHROMATIC, phase, true);
    furnace_case(
        "volpathmis furnace, tabphase, camera inside",
        &mis(&xml, ""),
    );
}

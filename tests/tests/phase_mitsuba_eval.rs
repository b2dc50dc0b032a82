//! The phase functions' values and densities against Mitsuba 3.9.1's own, at a grid of
//! directions: `tests/phase_cases/NAME.csv`, written from `NAME.xml` by
//! `scripts/mitsuba_phase_eval.py` (with the grid an `sggx` case names beside it). The case file's `<phase>` is loaded by Tessera's loader as a
//! file gives it. A control per case (a slightly different function) must disagree.
use glam::Vec3;
use std::path::PathBuf;
use tessera_core::medium::PhaseFunction;
use tessera_tests::phase::phase_from_xml;

fn cases_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("phase_cases")
}

/// The `<phase>` element of case `name`, a file it names (a grid beside it) made absolute.
fn case_phase_xml(name: &str) -> String {
    let text = std::fs::read_to_string(cases_dir().join(format!("{name}.xml"))).expect("case");
    let start = text.find("<phase").expect("a <phase>");
    let end = text.rfind("</scene>").expect("</scene>");
    let dir = format!("{}/", cases_dir().display());
    text[start..end].replace(
        "name=\"filename\" value=\"",
        &format!("name=\"filename\" value=\"{dir}"),
    )
}

/// Rows `(wi, wo, eval, pdf)` of case `name`'s table.
fn rows(name: &str) -> Vec<(Vec3, Vec3, f64, f64)> {
    let text = std::fs::read_to_string(cases_dir().join(format!("{name}.csv"))).expect("table");
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("wi_x"))
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().expect("number")).collect();
            let f = |i: usize| Vec3::new(v[i] as f32, v[i + 1] as f32, v[i + 2] as f32);
            (f(0), f(3), v[6], v[7])
        })
        .collect()
}

/// The largest relative difference between `p` and the table of case `name`.
fn worst(name: &str, p: &PhaseFunction) -> f64 {
    let mut worst = 0.0f64;
    for (wi, wo, e, d) in rows(name) {
        for (ours, theirs) in [(p.eval(wi, wo), e), (p.pdf(wi, wo), d)] {
            let rel = (f64::from(ours) - theirs).abs() / theirs.abs().max(1e-3);
            worst = worst.max(rel);
        }
    }
    worst
}

fn agrees(name: &str, control: &str) {
    let xml = case_phase_xml(name);
    let w = worst(name, &phase_from_xml(&xml));
    println!("{name}: worst relative difference {w:.3e}");
    assert!(w < 2e-4, "{name}: {w}");
    let edited = xml.replace(
        control.split('|').next().unwrap(),
        control.split('|').nth(1).unwrap(),
    );
    assert_ne!(edited, xml, "the control edit changes nothing");
    let c = worst(name, &phase_from_xml(&edited));
    println!("{name}, control: worst relative difference {c:.3e}");
    assert!(c > 1e-2, "{name}: the control agreed ({c})");
}

#[test]
fn rayleigh_matches_mitsuba() {
    agrees(
        "rayleigh",
        r#"type="rayleigh"/>|type="hg"><float name="g" value="0.05"/></phase>"#,
    );
}

#[test]
fn tabphase_smooth_matches_mitsuba() {
    agrees("tabphase_smooth", "1.5\"|1.6\"");
}

#[test]
fn tabphase_peaked_matches_mitsuba() {
    agrees("tabphase_peaked", " 20, 120\"| 20, 110\"");
}

#[test]
fn blendphase_hg_matches_mitsuba() {
    agrees("blendphase_hg", "value=\"0.3\"|value=\"0.32\"");
}

#[test]
fn sggx_matches_mitsuba() {
    agrees("sggx_skewed", "sggx_skewed.vol|sggx_skewed_control.vol");
}

#[test]
fn blendphase_nested_matches_mitsuba() {
    agrees("blendphase_nested", "value=\"0.25\"|value=\"0.3\"");
}

//! Shape groups and instances, and the cylinder, against Mitsuba 3 and against themselves.
//!
//! - `instances.xml` (a group of a cube and a sphere placed three times: rotated, non-uniformly
//!   scaled, mirrored) and `cylinder.xml` (a lit open cylinder, its inside visible, and an
//!   emitting one) render what Mitsuba 3.9.1 renders: region z-tests (8x8 blocks) against
//!   references made by scripts/mitsuba_instance_refs.py, Sidak-corrected to a 1% false-alarm
//!   rate. Controls that must fail: the second instance rotated 3 degrees further and scaled 5%
//!   taller; the lit cylinder's radius 4% larger.
//! - `dup_instanced.xml` and `dup_flat.xml` (the same geometry, instanced and written out by hand)
//!   render equivalently; control: the hand-written copy rotated 4 degrees.
//! - Bad input: located one-line errors.
use std::path::{Path, PathBuf};

use tessera_lab::stats::sidak_alpha;
use tessera_scene::image::RgbImage;
use tessera_scene::{load_scene, load_scene_str, LoadedScene};
use tessera_tests::{render_like_mitsuba, render_loaded, worst_against_reference_rect};

const BLOCK: u32 = 8;
const RES: u32 = 64;
const SPP: u64 = 256;
const REF_SPP: f64 = 2048.0;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("instances")
}

fn load(name: &str, defines: &[(&str, &str)]) -> LoadedScene {
    let d: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    let l = load_scene(&dir().join(name), &d).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(l.warnings.is_empty(), "{name}: {:?}", l.warnings);
    l
}

/// The worst region p-value of `l` (rendered with `seed`) against `reference`.
fn worst(l: &LoadedScene, reference: &RgbImage, ref_spp: f64, seed: u64) -> (f64, String) {
    let ours = render_loaded(l, SPP, seed);
    assert_eq!(ours.dropped(), 0, "non-finite samples");
    let like = render_like_mitsuba(l, SPP, seed + 1);
    worst_against_reference_rect(&ours, &like, SPP, reference, ref_spp, BLOCK)
}

fn alpha(comparisons: usize) -> f64 {
    sidak_alpha(
        0.01,
        comparisons * ((RES / BLOCK) * (RES / BLOCK) * 3) as usize,
    )
}

#[test]
fn instances_and_cylinders_match_mitsuba() {
    // Scene, and the control's change of one of its defaults (rz 35, sy 0.6, r 0.6).
    let cases = [
        ("instances", ("rz", "38")),
        ("instances", ("sy", "0.63")),
        ("cylinder", ("r", "0.624")),
    ];
    let a = alpha(2);
    let mut failures = Vec::new();
    for (i, (name, control)) in cases.iter().enumerate() {
        let path = dir().join("refs").join(format!("{name}.exr"));
        let reference = tessera::image_io::read_image(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let seed = 7000 + 10 * i as u64;
        if i != 1 {
            let (p, what) = worst(
                &load(&format!("{name}.xml"), &[]),
                &reference,
                REF_SPP,
                seed,
            );
            eprintln!("{name}: worst p = {p:.3e} at {what}");
            if p < a {
                failures.push(format!("{name}: p = {p:.3e} < {a:.3e} at {what}"));
            }
        }
        let l = load(&format!("{name}.xml"), &[*control]);
        let (pc, whatc) = worst(&l, &reference, REF_SPP, seed + 5);
        eprintln!("{name} control {control:?}: p = {pc:.3e} at {whatc}");
        if pc >= a {
            failures.push(format!(
                "{name}: control {control:?} went unnoticed (p = {pc:.3e})"
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "alpha {a:.3e}\n{}",
        failures.join("\n")
    );
}

/// Our render as a reference image (its mean per pixel).
fn image_of(l: &LoadedScene, spp: u64, seed: u64) -> (RgbImage, tessera::render::Framebuffer) {
    let fb = render_loaded(l, spp, seed);
    let img = RgbImage {
        width: fb.width,
        height: fb.height,
        data: fb.rgb(),
    };
    (img, fb)
}

#[test]
fn instanced_geometry_renders_as_the_same_geometry_written_out() {
    let inst = load("dup_instanced.xml", &[]);
    let flat = load("dup_flat.xml", &[]);
    let wrong = load("dup_flat.xml", &[("ra", "-56")]);
    // Both sides are our renders of SPP samples: the reference's variance is that of `like`.
    let ours = render_loaded(&inst, SPP, 11);
    let (reference, like) = image_of(&flat, SPP, 12);
    let a = alpha(1);
    let (p, what) = worst_against_reference_rect(&ours, &like, SPP, &reference, SPP as f64, BLOCK);
    eprintln!("instanced vs written out: worst p = {p:.3e} at {what}");
    assert!(
        p >= a,
        "instanced vs written out: p = {p:.3e} < {a:.3e} at {what}"
    );
    let (reference, like) = image_of(&wrong, SPP, 13);
    let (pc, whatc) =
        worst_against_reference_rect(&ours, &like, SPP, &reference, SPP as f64, BLOCK);
    eprintln!("control (copy rotated 4 degrees): p = {pc:.3e} at {whatc}");
    assert!(pc < a, "control went unnoticed: p = {pc:.3e}");
}

/// A scene with `body` and a camera; the load's error message.
fn error_of(body: &str) -> String {
    let text =
        format!("<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n{body}\n</scene>");
    match load_scene_str(&text, Path::new("t.xml"), &[]) {
        Ok(_) => panic!("loaded: {body}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_instancing_is_a_located_error() {
    let cases = [
        (
            "<shape type=\"instance\"><ref id=\"nope\"/></shape>",
            "t.xml:3:",
            "nope",
        ),
        (
            "<bsdf type=\"diffuse\" id=\"b\"/>\n<shape type=\"instance\"><ref id=\"b\"/></shape>",
            "t.xml:4:",
            "refers only to a shapegroup",
        ),
        ("<shape type=\"instance\"/>", "t.xml:3:", "needs a <ref"),
        (
            "<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"shapegroup\" id=\"h\"><shape \
             type=\"sphere\"/></shape>\n</shape>",
            "t.xml:4:",
            "nested shape groups",
        ),
        (
            "<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"sphere\">\n<emitter \
             type=\"area\"/></shape>\n</shape>\n<shape type=\"instance\"><ref id=\"g\"/></shape>",
            "t.xml:5:",
            "instancing of emitters is not supported",
        ),
        (
            "<shape type=\"shapegroup\" id=\"g\">\n<bsdf type=\"diffuse\"/>\n</shape>",
            "t.xml:4:",
            "holds only shapes",
        ),
        (
            "<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"/></shape>\n<shape \
             type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\"><scale \
             value=\"0\"/></transform></shape>",
            "t.xml:4:",
            "",
        ),
        (
            "<shape type=\"cylinder\"><point name=\"p1\" x=\"0\" y=\"0\" z=\"0\"/></shape>",
            "t.xml:3:",
            "p0 and p1 must differ",
        ),
        (
            "<shape type=\"cylinder\"><transform name=\"to_world\"><scale x=\"1\" y=\"2\" \
             z=\"1\"/></transform></shape>",
            "t.xml:3:",
            "cross-section a circle",
        ),
    ];
    for (body, at, what) in cases {
        let e = error_of(body);
        eprintln!("{e}");
        assert!(
            e.starts_with(at) || e.contains(&format!(" {at}")) || e.contains(at),
            "{body}\n{e}"
        );
        assert!(e.contains(what), "{body}\n{e}");
        assert_eq!(e.lines().count(), 1, "{e}");
    }
}

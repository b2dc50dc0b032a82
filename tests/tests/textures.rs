//! Textures (`bitmap`, `checkerboard`) and textured scalar parameters look up the same values
//! as Mitsuba 3 at many surface points, and bad texture input is a located error.
//!
//! Each `tests/uv_cases/NAME.xml` holds one `<bsdf>` with a textured parameter; `NAME.csv` was
//! written by `scripts/mitsuba_uv_eval.py` from Mitsuba 3.9.1 (scalar_rgb): eval (cosine
//! included) and pdf for one fixed pair of directions at 369 surface points inside and outside
//! the unit square (a grid and random points), which exercises the row order (`v = 0` is the
//! top row), pixel centres, bilinear and nearest filtering, the three wrap modes, `to_uv`, sRGB
//! decoding and `raw`, grey and EXR images, the other 8-bit formats (BMP, TGA and JPEG, made by
//! `scripts/make_8bit_textures.py`; sRGB-decoded unless `raw`, as PNG), nested textures, and
//! the scalar reading of a texture as a weight (luminance) or opacity. Tolerance: 1e-3 relative plus 1e-5 absolute, as
//! in `bsdf_mitsuba_eval.rs`.

use std::path::{Path, PathBuf};
use tessera_core::math::Norm;

use glam::{Vec2, Vec3};
use tessera_scene::{load_bsdf_file, load_scene_str};
use tessera_tests::bsdf::csv_rows;

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-3 * a.abs().max(b.abs()) + 1e-5
}

fn case_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("uv_cases")
}

fn wi() -> Vec3 {
    Vec3::new(0.3, 0.2, 0.9).unit()
}

fn wo() -> Vec3 {
    Vec3::new(-0.2, 0.1, 0.95).unit()
}

/// Mismatches of the material in `xml` against the table `csv`.
fn check(xml: &Path, csv: &Path) -> Vec<String> {
    let bsdf = match load_bsdf_file(xml) {
        Ok(b) => b,
        Err(e) => return vec![format!("{e}")],
    };
    let text = std::fs::read_to_string(csv)
        .unwrap_or_else(|e| panic!("{}: {e} (run scripts/mitsuba_uv_eval.py)", csv.display()));
    let mut bad = Vec::new();
    let mut rows = 0;
    for v in csv_rows(&text, "u,") {
        let uv = Vec2::new(v[0], v[1]);
        let want = Vec3::new(v[2], v[3], v[4]);
        let f = bsdf.eval(wi(), wo(), uv);
        let p = bsdf.pdf(wi(), wo(), uv);
        rows += 1;
        if !(0..3).all(|c| close(f[c], want[c])) || !close(p, v[5]) {
            bad.push(format!(
                "{}: uv {uv}: eval {f} (Mitsuba {want}), pdf {p} (Mitsuba {})",
                xml.display(),
                v[5]
            ));
        }
    }
    assert!(rows > 300, "{}: only {rows} rows", csv.display());
    bad
}

#[test]
fn textures_match_mitsuba_over_uv() {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(case_dir())
        .expect("tests/uv_cases exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    cases.sort();
    assert!(cases.len() >= 10, "{} cases", cases.len());
    let mut failures = Vec::new();
    for c in &cases {
        let bad = check(c, &c.with_extension("csv"));
        println!("{}: {} mismatches", c.display(), bad.len());
        failures.extend(bad.into_iter().take(5));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_wrong_lookup_is_caught() {
    // Controls: another filter / wrap mode, and raw codes instead of decoded sRGB, against the
    // default bilinear sRGB table.
    let d = case_dir();
    let table = d.join("bitmap_rgb.csv");
    for other in ["bitmap_nearest_mirror.xml", "bitmap_raw_mirror.xml"] {
        let bad = check(&d.join(other), &table);
        assert!(bad.len() > 100, "{other}: only {} mismatches", bad.len());
    }
    // Raw JPEG codes against the decoded JPEG table.
    let bad = check(
        &d.join("bitmap_jpeg_raw_mirror.xml"),
        &d.join("bitmap_jpeg.csv"),
    );
    assert!(bad.len() > 100, "raw JPEG: only {} mismatches", bad.len());
    // The checkerboard with its colours swapped.
    let swapped = std::env::temp_dir().join(format!("tessera_cb_{}.xml", std::process::id()));
    std::fs::write(
        &swapped,
        r#"<scene version="3.0.0"><bsdf type="diffuse"><texture type="checkerboard" name="reflectance"><float name="color0" value="0.2"/><float name="color1" value="0.4"/></texture></bsdf></scene>"#,
    )
    .unwrap();
    let bad = check(&swapped, &d.join("checkerboard_default.csv"));
    std::fs::remove_file(&swapped).ok();
    assert!(
        bad.len() > 100,
        "swapped checkerboard: {} mismatches",
        bad.len()
    );
}

/// The load error of a scene made of `bsdf` (one line of XML, so columns are easy to check).
fn error_of(bsdf: &str) -> String {
    let xml = format!("<scene version=\"3.0.0\">\n{bsdf}\n<sensor type=\"perspective\"/></scene>");
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("uv_cases/inline.xml");
    match load_scene_str(&xml, &path, &[]) {
        Ok(_) => panic!("{bsdf}: loaded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_textures_are_located_errors() {
    let tex = |body: &str| {
        format!(
            r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance">{body}</texture></bsdf>"#
        )
    };
    // (scene snippet, the element the error must point at, words of the message)
    let png = r#"<string name="filename" value="../../scenes/textures/tess_rgb.png"/>"#;
    let cases = [
        (
            tex(r#"<string name="filename" value="no_such.png"/>"#),
            "<string name=\"filename\"",
            "no_such.png",
        ),
        (tex(""), "<texture", "missing parameter \"filename\""),
        (
            tex(&format!(r#"{png}<string name="filter_type" value="cubic"/>"#)),
            "<string name=\"filter_type\"",
            "unknown filter_type \"cubic\"",
        ),
        (
            tex(&format!(r#"{png}<string name="wrap_mode" value="wrap"/>"#)),
            "<string name=\"wrap_mode\"",
            "unknown wrap_mode \"wrap\"",
        ),
        (
            tex(&format!(r#"{png}<float name="gamma" value="2"/>"#)),
            "<float name=\"gamma\"",
            "unused parameter \"gamma\"",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="noise" name="reflectance"/></bsdf>"#.into(),
            "<texture",
            "unknown texture \"noise\"",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="checkerboard" name="reflectance"><float name="color0" value="1.5"/></texture></bsdf>"#.into(),
            "<float name=\"color0\"",
            "\"color0\" of texture \"checkerboard\" must be in [0, 1]",
        ),
        (
            tex(&format!(r#"{png}<string name="format" value="half"/>"#)),
            "<string name=\"format\"",
            "unknown format \"half\"",
        ),
        (
            tex(r#"<string name="filename" value="../../scenes/textures/tess_linear.exr"/><string name="format" value="uint8"/>"#),
            "<string name=\"format\"",
            "format \"uint8\" of texture \"bitmap\" on the floating-point image",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="rawconstant" name="reflectance"/></bsdf>"#.into(),
            "<texture",
            "needs its parameter \"value\"",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="rawconstant" name="reflectance"><string name="value" value="red"/></texture></bsdf>"#.into(),
            "<string name=\"value\"",
            "must be a float or a vector, found string",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="rawconstant" name="reflectance"><vector name="value" value="0.5, -0.1, 0.2"/></texture></bsdf>"#.into(),
            "<vector name=\"value\"",
            "\"value\" of texture \"rawconstant\" must be in [0, 1]",
        ),
        (
            r#"<bsdf type="diffuse"><bsdf type="diffuse" name="reflectance"/></bsdf>"#.into(),
            "<bsdf type=\"diffuse\" name",
            "must be a texture or a value",
        ),
    ];
    for (bsdf, marker, needle) in cases {
        let col = bsdf.find(marker).expect("marker in snippet") + 1;
        let at = format!("inline.xml:2:{col}: ");
        let e = error_of(&bsdf);
        assert!(
            e.contains(&at) && e.contains(needle),
            "{bsdf}\n  -> {e} (expected {at})"
        );
    }
}

#[test]
fn out_of_range_pixels_are_errors() {
    // A linear image with a value above 1, as a reflectance and as a weight.
    let dir = std::env::temp_dir().join(format!("tessera_tex_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let img = tessera::image_io::RgbImage {
        width: 2,
        height: 1,
        data: vec![[0.5, 0.5, 0.5], [1.5, 0.2, 0.1]],
    };
    tessera::image_io::write_image(&dir.join("hot.exr"), &img).unwrap();
    let path = dir.join("s.xml");
    let xml = r#"<scene version="3.0.0"><bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="hot.exr"/></texture></bsdf></scene>"#;
    std::fs::write(&path, xml).unwrap();
    let e = load_bsdf_file(&path).unwrap_err().to_string();
    assert!(
        e.contains("s.xml:1:") && e.contains("pixel (1, 0)") && e.contains("[0, 1]"),
        "{e}"
    );
    let xml = r#"<scene version="3.0.0"><bsdf type="blendbsdf"><texture type="bitmap" name="weight"><string name="filename" value="hot.exr"/></texture><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf></scene>"#;
    std::fs::write(&path, xml).unwrap();
    let e = load_bsdf_file(&path).unwrap_err().to_string();
    assert!(e.contains("pixel (1, 0)"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn textures_can_be_declared_once_and_referenced() {
    // A top-level <texture id=...> used through <ref name=...>, twice.
    let xml = r#"<scene version="3.0.0">
    <texture type="checkerboard" id="cb"><float name="color0" value="0.9"/></texture>
    <bsdf type="diffuse" id="a"><ref name="reflectance" id="cb"/></bsdf>
    <bsdf type="mask" id="b"><ref name="opacity" id="cb"/><ref id="a"/></bsdf>
    <sensor type="perspective"/>
    </scene>"#;
    let path = case_dir().join("inline.xml");
    let scene = load_scene_str(xml, &path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let b = &scene.scene.bsdfs[0];
    let f = b.eval(Vec3::Z, Vec3::Z, Vec2::new(0.1, 0.1));
    assert!((f.x - 0.9 / std::f32::consts::PI).abs() < 1e-6, "{f}");
    let f = b.eval(Vec3::Z, Vec3::Z, Vec2::new(0.6, 0.1));
    assert!((f.x - 0.2 / std::f32::consts::PI).abs() < 1e-6, "{f}");
}

#[test]
fn checkerboard_scalar_lookup_picks_the_same_patch_as_the_colour() {
    // Mitsuba 3.9.1's checkerboard `eval_1` selects the opposite patch from its `eval` (its
    // source compares the two half-tests with `neq` in one and `eq` in the other); Tessera reads
    // a checkerboard weight or opacity from the patch whose colour it shows. As an opacity:
    // at uv (0.1, 0.1) the patch is color0.
    let xml = r#"<scene version="3.0.0"><bsdf type="mask"><texture type="checkerboard" name="opacity"><float name="color0" value="0.15"/><float name="color1" value="0.65"/></texture><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf><sensor type="perspective"/></scene>"#;
    let scene = load_scene_str(xml, &case_dir().join("inline.xml"), &[]).unwrap();
    let b = &scene.scene.bsdfs[0];
    let inv_pi = 1.0 / std::f32::consts::PI;
    for (uv, a) in [
        ((0.1, 0.1), 0.15),
        ((0.6, 0.1), 0.65),
        ((0.1, 0.7), 0.65),
        ((0.7, 0.8), 0.15),
    ] {
        let f = b.eval(Vec3::Z, Vec3::Z, Vec2::new(uv.0, uv.1));
        assert!((f.x - a * inv_pi).abs() < 1e-6, "uv {uv:?}: {f}");
    }
}

#[test]
fn extreme_uv_values_do_not_panic() {
    let b = load_bsdf_file(&case_dir().join("bitmap_clamp_to_uv.xml")).unwrap();
    let c = load_bsdf_file(&case_dir().join("bitmap_nearest_mirror.xml")).unwrap();
    for v in [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        -f32::MAX,
        1e30,
    ] {
        for uv in [Vec2::new(v, 0.3), Vec2::new(0.3, v), Vec2::splat(v)] {
            assert!(b.eval(wi(), wo(), uv).is_finite(), "{uv}");
            assert!(c.eval(wi(), wo(), uv).is_finite(), "{uv}");
        }
    }
}

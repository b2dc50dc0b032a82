//! Helpers shared by the material tests: build one `<bsdf>` from XML text, directions by angle,
//! the chi-square configuration and check, the located-error check for bad parameters, and the
//! case files of `tests/bsdf_cases/` with their tables of Mitsuba's values.
use glam::{Vec2, Vec3};
use tessera_core::bsdf::Bsdf;
use tessera_lab::stats::{sidak_alpha, BsdfChi2, Chi2Result};
use tessera_scene::error::InputError;
use tessera_scene::xml::Kind;

/// Builds the first `<bsdf>` of `xml`, written inside `<scene version="3.0.0">` (Mitsuba 3) or,
/// with `nori`, inside a plain `<scene>` (Nori's camelCase names). The text is read as if it
/// were `scenes/case.xml`, so relative paths resolve in `scenes/`; the snippet starts on line 2.
pub fn build_bsdf_xml(xml: &str, nori: bool) -> Result<Bsdf, InputError> {
    let open = if nori {
        "<scene>"
    } else {
        "<scene version=\"3.0.0\">"
    };
    let text = format!("{open}\n{xml}\n</scene>\n");
    let path = crate::scenes_dir().join("case.xml");
    let root = tessera_scene::xml::load_str(&text, &path, &[])?;
    let child = root
        .children_of(Kind::Bsdf)
        .next()
        .ok_or_else(|| root.error("no <bsdf> in the snippet"))?;
    tessera_scene::build_bsdf_object(&child.obj)
}

/// [`build_bsdf_xml`] for Mitsuba 3 syntax, panicking with the error.
pub fn load_bsdf_xml(xml: &str) -> Bsdf {
    build_bsdf_xml(xml, false).unwrap_or_else(|e| panic!("{e}\n{xml}"))
}

/// The unit direction at polar angle `deg` degrees and azimuth `phi` radians.
pub fn dir_at(deg: f32, phi: f32) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// The direction of `u` uniform on the upper hemisphere, or with `both_sides` on the sphere.
pub fn uniform_direction(u: Vec2, both_sides: bool) -> Vec3 {
    let z = if both_sides { 2.0 * u.x - 1.0 } else { u.x };
    let r = (1.0 - z * z).max(0.0).sqrt();
    let p = std::f32::consts::TAU * u.y;
    Vec3::new(r * p.cos(), r * p.sin(), z)
}

/// BsdfChi2's grid (20 x 40 cells) with half its default sample count, to keep files fast.
pub const CHI2_HALF: BsdfChi2 = BsdfChi2 {
    theta_bins: 20,
    phi_bins: 40,
    samples: 500_000,
};

/// Asserts that chi-square result `r` (printed with `name`) passes at the Šidák level of 0.01
/// over the `n_tests` chi-square tests of the file.
pub fn assert_chi2_passes(name: &str, r: &Chi2Result, n_tests: usize) {
    let a = sidak_alpha(0.01, n_tests);
    println!("{name}: {r}");
    assert!(r.passes(a), "{name}: {r} (alpha = {a:.3e})");
}

/// A microfacet `plugin` (`roughconductor`, `roughdielectric`) with distribution `dist`,
/// roughness `(au, av)`, `sample_visible` = `visible` and the `extra` property lines.
pub fn rough_xml(plugin: &str, dist: &str, au: f32, av: f32, visible: bool, extra: &str) -> String {
    format!(
        r#"<bsdf type="{plugin}">
            <string name="distribution" value="{dist}"/>
            <float name="alpha_u" value="{au}"/> <float name="alpha_v" value="{av}"/>
            <boolean name="sample_visible" value="{visible}"/> {extra}
        </bsdf>"#
    )
}

/// `props` inside `<bsdf type="plugin">` (Mitsuba 3 syntax) must be rejected with one line that
/// contains `words` and points at `case.xml:line:column` of the tag of the property `prop` (or,
/// when no property has that name, where the text `prop` starts).
pub fn assert_bad_bsdf(plugin: &str, props: &str, prop: &str, words: &str) {
    let xml = format!("<bsdf type=\"{plugin}\">\n{props}\n</bsdf>");
    let err = match build_bsdf_xml(&xml, false) {
        Ok(_) => panic!("accepted: {xml}"),
        Err(e) => e.to_string(),
    };
    println!("{err}");
    let text = format!("<scene version=\"3.0.0\">\n{xml}\n</scene>\n");
    let at = match text.find(&format!("name=\"{prop}\"")) {
        Some(i) => text[..i].rfind('<').unwrap(),
        None => text.find(prop).expect("prop in the text"),
    };
    let line = text[..at].matches('\n').count() + 1;
    let col = at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
    let want = format!("case.xml:{line}:{col}:");
    assert!(err.contains(&want), "{err:?} does not start at {want}");
    assert!(err.contains(words), "{err:?} does not say {words:?}");
    assert!(!err.contains('\n'), "{err:?}");
}

/// Each `(plugin, property lines, words)` case, written as `<bsdf type="plugin">` with the
/// properties on its second line (Mitsuba 3 syntax, or Nori's when `nori`), must be rejected with
/// an error located on line 3 of the case file (the property's line) that contains `words`.
pub fn assert_cases_rejected_on_their_line(cases: &[(&str, &str, &str)], nori: bool) {
    for (plugin, prop, needle) in cases {
        let xml = format!("<bsdf type=\"{plugin}\">\n{prop}</bsdf>");
        let e = match build_bsdf_xml(&xml, nori) {
            Ok(_) => panic!("{plugin} with {prop} was accepted"),
            Err(e) => e,
        };
        let text = e.to_string();
        println!("{text}");
        assert!(text.contains(needle), "{text}");
        assert_eq!(e.loc.as_ref().map(|l| l.line), Some(3), "{text}");
    }
}

/// The material files of `tests/bsdf_cases/` (`*.xml`, each beside the CSV table of Mitsuba's
/// values that `scripts/mitsuba_bsdf_eval.py` made), sorted by name.
pub fn bsdf_case_files() -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_cases");
    let mut v: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/bsdf_cases exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    v.sort();
    v
}

/// The numeric rows of a CSV table of reference values: every line but comments (`#`) and the
/// header (the line starting with `header`), split at commas and parsed.
pub fn csv_rows<'a>(text: &'a str, header: &'a str) -> impl Iterator<Item = Vec<f32>> + 'a {
    text.lines()
        .filter(move |l| !l.starts_with('#') && !l.starts_with(header))
        .map(|line| line.split(',').map(|x| x.parse().unwrap()).collect())
}

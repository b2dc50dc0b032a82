//! `<spectrum>` values against Mitsuba 3: the colours below are what Mitsuba 3.9.1's
//! scalar_rgb variant builds for the same elements (printed by
//! `scripts/mitsuba_spectrum_rgb.py`, which loads each case through Mitsuba itself).
use super::*;

const REFLECTANCE_S: &str =
    "400:0.092, 450:0.104, 500:0.285, 550:0.4, 600:0.16, 650:0.118, 700:0.159";
const SATURATED_S: &str = "400:0, 560:0, 580:1, 700:1";
const LIGHT_S: &str = "400:0, 500:8, 600:15.6, 700:18.4";
const ETA_S: &str = "300:1.8, 400:1.65, 500:0.9, 600:0.2, 700:0.16, 800:0.18";
const K_S: &str = "300:1.92, 400:1.95, 500:1.95, 600:2.97, 700:3.8, 800:5.12";

const REFLECTANCE: [f64; 3] = [0.11145477, 0.35320434, 0.119110554];
const SATURATED: [f64; 3] = [1.0, 0.123971328, 0.0];
const LIGHT: [f64; 3] = [20.7108364, 10.8546343, 2.77115202];
const FLAT_LIGHT: [f64; 3] = [2.40958786, 1.89658201, 1.81783211];
const ETA: [f64; 3] = [0.0452340953, 0.585708857, 1.33692372];
const K: [f64; 3] = [3.38869143, 2.34904099, 1.87515724];

/// The value of property `name` of the first child of the scene `body`.
fn value_of(body: &str, name: &str) -> Value {
    let s = load(&format!("<scene version=\"3.0.0\">\n{body}\n</scene>"));
    let obj = &s.children[0].obj;
    obj.props
        .iter()
        .find(|p| p.name == name)
        .unwrap()
        .value
        .clone()
}

fn rgb_of(body: &str, name: &str) -> [f64; 3] {
    match value_of(body, name) {
        Value::Rgb(c) => c,
        other => panic!("expected an rgb, found {other:?}"),
    }
}

/// Mitsuba computes in single precision: agreement to 1e-5, relative.
fn agrees(got: [f64; 3], want: [f64; 3]) -> bool {
    (0..3).all(|i| (got[i] - want[i]).abs() <= 1e-5 * want[i].abs().max(1.0))
}

#[test]
fn spectra_convert_as_mitsuba_does() {
    let cases = [
        (format!("<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"{REFLECTANCE_S}\"/></bsdf>"), "reflectance", REFLECTANCE),
        (format!("<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"{SATURATED_S}\"/></bsdf>"), "reflectance", SATURATED),
        (format!("<emitter type=\"point\"><spectrum name=\"intensity\" value=\"{LIGHT_S}\"/></emitter>"), "intensity", LIGHT),
        ("<emitter type=\"point\"><spectrum name=\"intensity\" value=\"2\"/></emitter>".to_string(), "intensity", FLAT_LIGHT),
        (format!("<bsdf type=\"conductor\"><spectrum name=\"eta\" value=\"{ETA_S}\"/></bsdf>"), "eta", ETA),
        (format!("<bsdf type=\"conductor\"><spectrum name=\"k\" value=\"{K_S}\"/></bsdf>"), "k", K),
    ];
    for (body, name, want) in &cases {
        let got = rgb_of(body, name);
        assert!(agrees(got, *want), "{body}: got {got:?}, Mitsuba {want:?}");
    }
    // A single value is grey except for emitted light.
    let grey = value_of(
        "<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"0.5\"/></bsdf>",
        "reflectance",
    );
    assert_eq!(grey, Value::Float(0.5));
}

#[test]
fn control_the_context_matters() {
    // The same list read as a reflectance (D65-weighted, clamped) is far from Mitsuba's
    // emitted colour, and the reflectance read as light (unweighted) is far from Mitsuba's
    // reflectance colour: a conversion that ignored the context would fail the test above.
    let as_reflectance = rgb_of(
        &format!(
            "<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"{LIGHT_S}\"/></bsdf>"
        ),
        "reflectance",
    );
    assert!(!agrees(as_reflectance, LIGHT), "{as_reflectance:?}");
    let as_light = rgb_of(
        &format!("<emitter type=\"point\"><spectrum name=\"intensity\" value=\"{REFLECTANCE_S}\"/></emitter>"),
        "intensity",
    );
    assert!(!agrees(as_light, REFLECTANCE), "{as_light:?}");
    // Unbounded parameters are not clamped: k read as a (clamped) reflectance is different.
    let clamped = rgb_of(
        &format!("<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"{K_S}\"/></bsdf>"),
        "reflectance",
    );
    assert!(!agrees(clamped, K), "{clamped:?}");
}

#[test]
fn spectrum_files_and_errors() {
    let d = temp_dir();
    let mut spd = String::from("# wavelength value\n");
    for pair in super::super::values::split_list(REFLECTANCE_S) {
        let (w, v) = pair.split_once(':').unwrap();
        spd.push_str(&format!("{w} {v}\n"));
    }
    std::fs::write(d.join("r.spd"), spd).unwrap();
    let main = d.join("main.xml");
    let s = load_str(
        "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" filename=\"r.spd\"/></bsdf>\n</scene>",
        &main,
        &[],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    match &s.children[0].obj.props[0].value {
        Value::Rgb(c) => assert!(agrees(*c, REFLECTANCE), "{c:?}"),
        other => panic!("{other:?}"),
    }
    let at = |body: &str| {
        let text =
            format!("<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">{body}</bsdf>\n</scene>");
        load_str(&text, &main, &[]).unwrap_err().to_string()
    };
    let here = |col: u32| format!("{}:2:{col}: ", main.display());
    let e = at("<spectrum name=\"reflectance\" value=\"500:0.1, 400:0.2\"/>");
    assert!(
        e.starts_with(&here(51)) && e.contains("wavelengths must increase"),
        "{e}"
    );
    let e = at("<spectrum name=\"reflectance\" value=\"400:0.1\"/>");
    assert!(
        e.starts_with(&here(51)) && e.contains("at least two"),
        "{e}"
    );
    let e = at("<spectrum name=\"reflectance\" value=\"0.1\" filename=\"r.spd\"/>");
    assert!(e.starts_with(&here(63)) && e.contains("not both"), "{e}");
    let e = at("<spectrum name=\"reflectance\"/>");
    assert!(
        e.starts_with(&here(22)) && e.contains("needs a \"value\""),
        "{e}"
    );
    let e = at("<spectrum name=\"reflectance\" filename=\"none.spd\"/>");
    assert!(e.starts_with(&here(51)) && e.contains("none.spd"), "{e}");
}

#[test]
fn clamping_is_warned_where_the_spectrum_is() {
    let warnings = |list: &str| {
        let text = format!(
            "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"{list}\"/></bsdf>\n</scene>"
        );
        load(&text).load_warnings.clone()
    };
    let w = warnings(SATURATED_S);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].starts_with(&format!("{P}:2:22: the spectrum's colour [1.3186")),
        "{w:?}"
    );
    assert!(
        w[0].contains("clamped to [1.0000, 0.1240, 0.0000]"),
        "{w:?}"
    );
    // Control: an in-gamut spectrum warns of nothing.
    assert!(warnings(REFLECTANCE_S).is_empty());
}

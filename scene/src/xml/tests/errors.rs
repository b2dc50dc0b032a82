//! Errors of every kind, each located at file:line:column, and hostile input.
use super::*;

#[test]
fn structural_errors() {
    assert_err("<scene>\n  <foo/>\n</scene>", 2, 3, "unknown element <foo>");
    assert_err(
        "<scene>\n  <tensor type=\"data\"/>\n</scene>",
        2,
        3,
        "unsupported element <tensor type=\"data\">",
    );
    assert_err(
        "<scene>\n  <shape type=\"sphere\" colour=\"x\"/>\n</scene>",
        2,
        24,
        "unknown attribute \"colour\"",
    );
    assert_err(
        "<scene>\n  <shape id=\"a\"/>\n</scene>",
        2,
        3,
        "<shape> is missing the \"type\" attribute",
    );
    assert_err(
        "<scene>\n  <float value=\"1\"/>\n</scene>",
        2,
        3,
        "<float> is missing the \"name\" attribute",
    );
    assert_err(
        "<scene>\n  <float name=\"a\"/>\n</scene>",
        2,
        3,
        "missing the \"value\"",
    );
    assert_err(
        "<shape type=\"sphere\"/>",
        1,
        1,
        "the root element must be <scene>",
    );
    assert_err(
        "<scene>\n  <scene/>\n</scene>",
        2,
        3,
        "only allowed as the root",
    );
    assert_err(
        "<scene>\n  <translate x=\"1\"/>\n</scene>",
        2,
        3,
        "only allowed inside <transform>",
    );
    assert_err(
        "<scene><shape type=\"sphere\">\n  <transform name=\"t\"><float name=\"a\" value=\"1\"/></transform></shape></scene>",
        2,
        23,
        "not allowed inside <transform>",
    );
    assert_err(
        "<scene>\n  <float name=\"a\" value=\"1\"><b/></float>\n</scene>",
        2,
        29,
        "cannot contain elements",
    );
    assert_err(
        "<scene>\n  hello\n</scene>",
        2,
        3,
        "unexpected text \"hello\"",
    );
    assert_err("<scene version=\"three\"/>", 1, 8, "invalid version");
    assert_err(
        "<scene>\n  <shape type=\"\"/>\n</scene>",
        2,
        10,
        "must not be empty",
    );
}

#[test]
fn value_errors() {
    assert_err(
        "<scene>\n  <float name=\"a\" value=\"abc\"/>\n</scene>",
        2,
        19,
        "\"abc\" is not a number",
    );
    assert_err(
        "<scene>\n  <integer name=\"a\" value=\"1.5\"/>\n</scene>",
        2,
        21,
        "not an integer",
    );
    assert_err(
        "<scene>\n  <boolean name=\"a\" value=\"yes\"/>\n</scene>",
        2,
        21,
        "not a boolean",
    );
    assert_err(
        "<scene>\n  <rgb name=\"a\" value=\"1 2\"/>\n</scene>",
        2,
        17,
        "has 2 numbers",
    );
    assert_err(
        "<scene>\n  <spectrum name=\"a\" value=\"400:0.1, 500\"/>\n</scene>",
        2,
        22,
        "\"500\" is not a wavelength:value pair",
    );
    assert_err(
        "<scene>\n  <spectrum name=\"a\" value=\"0.1 0.2\"/>\n</scene>",
        2,
        22,
        "is not a wavelength:value pair",
    );
    assert_err(
        "<scene>\n  <spectrum name=\"a\" filename=\"x.spd\"/>\n</scene>",
        2,
        22,
        "x.spd\": cannot read file",
    );
    assert_err(
        "<scene>\n  <point name=\"p\"/>\n</scene>",
        2,
        3,
        "needs a \"value\"",
    );
    assert_err(
        "<scene>\n  <point name=\"p\" value=\"1 2 3\" x=\"1\"/>\n</scene>",
        2,
        3,
        "not both",
    );
    assert_err(
        "<scene><sensor type=\"x\">\n<transform name=\"t\">\n  <matrix value=\"1 2 3\"/>\n</transform></sensor></scene>",
        3,
        11,
        "expected 16",
    );
    assert_err(
        "<scene><sensor type=\"x\">\n<transform name=\"t\">\n  <rotate angle=\"10\"/>\n</transform></sensor></scene>",
        3,
        3,
        "needs an axis",
    );
    assert_err(
        "<scene><sensor type=\"x\">\n<transform name=\"t\">\n  <lookat origin=\"0 0 0\" target=\"0 1 0\" up=\"0 1 0\"/>\n</transform></sensor></scene>",
        3,
        3,
        "parallel",
    );
    assert_err(
        "<scene><shape type=\"s\">\n  <float name=\"r\" value=\"1\"/>\n  <rgb name=\"r\" value=\"1\"/>\n</shape></scene>",
        3,
        3,
        "parameter \"r\" of shape \"s\" is specified twice (first at dir/scene.xml:2:3)",
    );
}

#[test]
fn parameter_errors() {
    assert_err(
        "<scene>\n  <integer name=\"spp\" value=\"$spp\"/>\n</scene>",
        2,
        23,
        "unknown parameter \"$spp\"",
    );
    // A use before the <default> is unknown too: defaults apply from where they appear.
    assert_err(
        "<scene>\n  <integer name=\"spp\" value=\"$spp\"/>\n  <default name=\"spp\" value=\"1\"/>\n</scene>",
        2,
        23,
        "unknown parameter",
    );
    assert_err(
        "<scene>\n  <default name=\"a b\" value=\"1\"/>\n</scene>",
        2,
        12,
        "not a valid parameter name",
    );
}

#[test]
fn ref_and_id_errors() {
    assert_err(
        "<scene>\n  <shape type=\"sphere\">\n    <ref id=\"nope\"/>\n  </shape>\n</scene>",
        3,
        5,
        "unknown id \"nope\"",
    );
    // A reference may come before its declaration, but a cycle through one is refused at
    // the reference that closes it.
    assert_err(
        "<scene>\n  <shape type=\"s\" id=\"a\"><ref id=\"b\"/></shape>\n  <bsdf type=\"d\" id=\"b\">\n    <ref id=\"a\"/>\n  </bsdf>\n</scene>",
        4,
        5,
        "reference cycle: id \"a\"",
    );
    assert_err(
        "<scene>\n  <alias id=\"later\" as=\"x\"/>\n  <bsdf type=\"d\" id=\"later\"/>\n</scene>",
        2,
        10,
        "unknown id \"later\" (an alias needs its object declared before it)",
    );
    assert_err(
        "<scene>\n  <bsdf type=\"diffuse\" id=\"m\"/>\n  <bsdf type=\"conductor\" id=\"m\"/>\n</scene>",
        3,
        26,
        "duplicate id \"m\" (first declared at dir/scene.xml:2:3)",
    );
    assert_err(
        "<scene>\n  <shape type=\"s\" id=\"m\">\n    <ref id=\"m\"/>\n  </shape>\n</scene>",
        3,
        5,
        "contains this reference",
    );
}

#[test]
fn xml_syntax_errors_are_located() {
    let e = load_err("<scene>\n  <shape type=\"sphere\">\n</scene>");
    assert!(e.starts_with("dir/scene.xml:3:"), "{e}");
    let e = load_err("<scene>\n  <float name=\"a\" value=\"1\" value=\"2\"/>\n</scene>");
    assert!(e.starts_with("dir/scene.xml:2:"), "{e}");
    let e = load_err("<!DOCTYPE x [<!ENTITY a \"b\">]><scene/>");
    assert!(e.starts_with("dir/scene.xml:1:1: "), "{e}");
    let e = load_err("<?xml version=\"1.0\"?>\n  <!DOCTYPE x><scene/>");
    assert!(e.starts_with("dir/scene.xml:2:3: "), "{e}");
}

#[test]
fn getter_errors_and_unused() {
    let s = load(
        "<scene>\n  <shape type=\"sphere\">\n    <string name=\"radius\" value=\"big\"/>\n    <float name=\"foo\" value=\"1\"/>\n    <bsdf type=\"diffuse\"/>\n  </shape>\n</scene>",
    );
    let sh = &s.children[0].obj;
    let e = sh.float("radius", 1.0).unwrap_err().to_string();
    assert_eq!(
        e,
        "dir/scene.xml:3:5: parameter \"radius\" of shape \"sphere\" must be a float, found string"
    );
    let e = sh.check_unused().unwrap_err().to_string();
    assert_eq!(
        e,
        "dir/scene.xml:4:5: unused parameter \"foo\" in shape \"sphere\""
    );
    sh.float("foo", 0.0).unwrap();
    let e = sh.check_unused().unwrap_err().to_string();
    assert_eq!(
        e,
        "dir/scene.xml:5:5: unused bsdf \"diffuse\" in shape \"sphere\""
    );
    sh.children[0].mark_used();
    sh.check_unused().unwrap();
    let e = s.check_unused().unwrap_err().to_string();
    assert_eq!(e, "dir/scene.xml:2:3: unused shape \"sphere\" in scene");
}

#[test]
fn hostile_nesting_and_size() {
    // Deep nesting: a clean error, no stack overflow (also in roxmltree itself).
    let n = 100_000;
    let mut text = String::from("<scene>");
    for _ in 0..n {
        text.push_str("<shape type=\"a\">");
    }
    for _ in 0..n {
        text.push_str("</shape>");
    }
    text.push_str("</scene>");
    let e = load_err(&text);
    assert!(e.contains("nested deeper than 64 levels"), "{e}");
    assert!(e.starts_with("dir/scene.xml:1:"), "{e}");

    // 63 levels below the root are fine.
    let mut ok = String::from("<scene>");
    for _ in 0..63 {
        ok.push_str("<bsdf type=\"a\">");
    }
    for _ in 0..63 {
        ok.push_str("</bsdf>");
    }
    ok.push_str("</scene>");
    load(&ok);

    let big = " ".repeat(MAX_FILE_BYTES as usize + 1);
    let e = load_str(&big, Path::new(P), &[]).unwrap_err().to_string();
    assert!(e.starts_with("dir/scene.xml: file is too large"), "{e}");
}

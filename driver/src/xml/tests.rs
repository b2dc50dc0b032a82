//! End-to-end tests of the XML layer through [`load_str`] and [`load_file`].

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use glam::{DMat4, DVec3, DVec4};

use super::*;

const P: &str = "dir/scene.xml";

fn load(text: &str) -> Object {
    load_str(text, Path::new(P), &[]).unwrap_or_else(|e| panic!("{e}"))
}

fn load_err(text: &str) -> String {
    match load_str(text, Path::new(P), &[]) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

/// Asserts an error message starts with `dir/scene.xml:line:col: ` and contains `needle`.
fn assert_err(text: &str, line: u32, col: u32, needle: &str) {
    let e = load_err(text);
    let want = format!("{P}:{line}:{col}: ");
    assert!(e.starts_with(&want), "expected prefix {want:?}, got {e:?}");
    assert!(e.contains(needle), "expected {needle:?} in {e:?}");
    assert!(!e.contains('\n'));
}

fn defs(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

fn close(a: DMat4, b: DMat4) -> bool {
    a.abs_diff_eq(b, 1e-12)
}

/// A fresh directory under the temp dir.
fn temp_dir() -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let d = std::env::temp_dir().join(format!(
        "tessera-xml-test-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn properties_of_every_type() {
    let s = load(
        r#"<scene version="3.0.0">
  <integrator type="path">
    <integer name="max_depth" value="-1"/>
    <float name="f" value="1e-3"/>
    <float name="fi" value="2"/>
    <boolean name="b" value="True"/>
    <string name="s" value="a b, c"/>
    <rgb name="c1" value="0.5"/>
    <rgb name="c3" value="0.1, 0.2, 0.3"/>
    <rgb name="c3s" value="0.1 0.2 0.3"/>
    <spectrum name="sp" value="0.25"/>
    <point name="p" value="1, 2, 3"/>
    <point name="pa" x="1" z="3"/>
    <vector name="v" x="0" y="1" z="0"/>
  </integrator>
</scene>"#,
    );
    assert_eq!(s.kind, Kind::Scene);
    assert_eq!(s.plugin, "");
    assert_eq!(s.children.len(), 1);
    let i = &s.children[0].obj;
    assert_eq!((i.kind, i.plugin.as_str()), (Kind::Integrator, "path"));
    assert_eq!((i.loc.line, i.loc.col), (2, 3));
    assert_eq!(i.integer("max_depth", 0).unwrap(), -1);
    assert_eq!(i.float("f", 0.0).unwrap(), 1e-3);
    assert_eq!(i.float("fi", 0.0).unwrap(), 2.0);
    assert!(i.boolean("b", false).unwrap());
    assert_eq!(i.string("s", "").unwrap(), "a b, c");
    assert_eq!(i.rgb("c1", [0.0; 3]).unwrap(), [0.5; 3]);
    assert_eq!(i.rgb("c3", [0.0; 3]).unwrap(), [0.1, 0.2, 0.3]);
    assert_eq!(i.rgb("c3s", [0.0; 3]).unwrap(), [0.1, 0.2, 0.3]);
    assert_eq!(i.rgb("sp", [0.0; 3]).unwrap(), [0.25; 3]);
    assert_eq!(i.float("sp", 0.0).unwrap(), 0.25);
    assert_eq!(i.point("p", [0.0; 3]).unwrap(), [1.0, 2.0, 3.0]);
    assert_eq!(i.point("pa", [9.0; 3]).unwrap(), [1.0, 0.0, 3.0]);
    assert_eq!(i.vector("v", [0.0; 3]).unwrap(), [0.0, 1.0, 0.0]);
    i.check_unused().unwrap();
    let p = &i.props[0];
    assert_eq!(
        (p.name.as_str(), p.loc.line, p.loc.col),
        ("max_depth", 3, 5)
    );
    assert_eq!(p.loc.file.as_path(), Path::new(P));
}

#[test]
fn nested_objects_and_names() {
    let s = load(
        r#"<scene version="3.0.0">
  <shape type="sphere" id="ball">
    <bsdf type="diffuse">
      <texture type="checkerboard" name="reflectance"/>
    </bsdf>
  </shape>
</scene>"#,
    );
    let shape = &s.children[0].obj;
    assert_eq!(shape.id.as_deref(), Some("ball"));
    let bsdf = &shape.children[0];
    assert_eq!(bsdf.obj.kind, Kind::Bsdf);
    assert!(bsdf.name.is_none() && !bsdf.is_ref);
    let tex = bsdf.obj.child("reflectance").unwrap();
    assert_eq!(tex.obj.kind, Kind::Texture);
    assert_eq!(tex.obj.name.as_deref(), Some("reflectance"));
    assert_eq!((tex.loc.line, tex.loc.col), (4, 7));
    bsdf.obj.check_unused().unwrap();
    assert_eq!(shape.children_of(Kind::Bsdf).count(), 1);
}

#[test]
fn transform_order_and_ops() {
    let s = load(
        r#"<scene version="3.0.0">
  <shape type="sphere">
    <transform name="to_world">
      <translate x="1" y="2" z="3"/>
      <rotate y="1" angle="90"/>
    </transform>
    <transform name="b">
      <scale value="2"/>
      <scale x="3"/>
      <translate value="1 0 0"/>
    </transform>
    <transform name="m">
      <matrix value="1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1"/>
    </transform>
    <transform name="r">
      <rotate axis="0, 0, 2" angle="90"/>
    </transform>
    <transform name="e"/>
  </shape>
</scene>"#,
    );
    let sh = &s.children[0].obj;
    let t = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0));
    let r = DMat4::from_axis_angle(DVec3::Y, 90f64.to_radians());
    let m = sh.transform_opt("to_world").unwrap().unwrap();
    assert!(close(m, r * t), "{m:?}");
    // Rotating (1,2,3) by 90 degrees about +y (right-handed) gives (3,2,-1).
    let o = m.transform_point3(DVec3::ZERO);
    assert!((o - DVec3::new(3.0, 2.0, -1.0)).length() < 1e-12, "{o:?}");

    let b = sh.transform_opt("b").unwrap().unwrap();
    let p = b.transform_point3(DVec3::new(1.0, 1.0, 1.0));
    assert!((p - DVec3::new(7.0, 2.0, 2.0)).length() < 1e-12, "{p:?}");

    let mm = sh.transform_opt("m").unwrap().unwrap();
    assert_eq!(mm.w_axis, DVec4::new(5.0, 6.0, 7.0, 1.0));

    let rr = sh.transform_opt("r").unwrap().unwrap();
    let x = rr.transform_vector3(DVec3::X);
    assert!((x - DVec3::Y).length() < 1e-12, "{x:?}");
    assert_eq!(sh.transform_opt("e").unwrap(), Some(DMat4::IDENTITY));
}

#[test]
fn lookat_columns() {
    let s = load(
        r#"<scene>
  <sensor type="perspective">
    <transform name="to_world">
      <lookat origin="0, 0, 5" target="0 0 0" up="0, 1, 0"/>
    </transform>
    <transform name="t2">
      <lookat origin="1 2 3" target="1 2 4"/>
    </transform>
  </sensor>
</scene>"#,
    );
    let sen = &s.children[0].obj;
    let m = sen.transform_opt("to_world").unwrap().unwrap();
    // dir = (0,0,-1); left = up x dir = (-1,0,0); new_up = dir x left = (0,1,0).
    let want = DMat4::from_cols(
        DVec4::new(-1.0, 0.0, 0.0, 0.0),
        DVec4::new(0.0, 1.0, 0.0, 0.0),
        DVec4::new(0.0, 0.0, -1.0, 0.0),
        DVec4::new(0.0, 0.0, 5.0, 1.0),
    );
    assert!(close(m, want), "{m:?}");
    // Without "up", some perpendicular up is chosen; the frame stays orthonormal.
    let m2 = sen.transform_opt("t2").unwrap().unwrap();
    assert!((m2.z_axis.truncate() - DVec3::Z).length() < 1e-12);
    assert!(m2.x_axis.truncate().dot(DVec3::Z).abs() < 1e-12);
    assert!((m2.x_axis.truncate().length() - 1.0).abs() < 1e-12);
    assert_eq!(m2.w_axis, DVec4::new(1.0, 2.0, 3.0, 1.0));
}

#[test]
fn defaults_and_defines() {
    let text = r#"<scene version="3.0.0">
  <default name="spp" value="64"/>
  <default name="res" value="32"/>
  <sampler type="independent">
    <integer name="sample_count" value="$spp"/>
    <string name="label" value="spp=$spp res=$res!"/>
  </sampler>
  <default name="spp" value="999"/>
</scene>"#;
    let s = load(text);
    let smp = &s.children[0].obj;
    assert_eq!(smp.integer("sample_count", 0).unwrap(), 64);
    assert_eq!(smp.string("label", "").unwrap(), "spp=64 res=32!");

    let s = load_str(text, Path::new(P), &defs(&[("spp", "8")])).unwrap();
    let smp = &s.children[0].obj;
    assert_eq!(smp.integer("sample_count", 0).unwrap(), 8);
    // A define can also supply a parameter with no <default>.
    let s = load_str(
        r#"<scene><shape type="$t"/></scene>"#,
        Path::new(P),
        &defs(&[("t", "sphere")]),
    )
    .unwrap();
    assert_eq!(s.children[0].obj.plugin, "sphere");
}

#[test]
fn refs_and_aliases() {
    let s = load(
        r#"<scene version="3.0.0">
  <bsdf type="diffuse" id="white"/>
  <shape type="sphere">
    <ref id="white"/>
  </shape>
  <shape type="cube">
    <bsdf type="conductor" id="metal"/>
  </shape>
  <alias id="metal" as="shiny"/>
  <shape type="rectangle">
    <ref id="shiny" name="bsdf"/>
  </shape>
</scene>"#,
    );
    let decl = &s.children[0];
    let r1 = &s.children[1].obj.children[0];
    assert!(std::rc::Rc::ptr_eq(&decl.obj, &r1.obj));
    assert!(r1.is_ref && r1.name.is_none());
    assert_eq!((r1.loc.line, r1.loc.col), (4, 5));
    assert!(decl.obj.is_referenced());
    let metal = &s.children[2].obj.children[0].obj;
    let r2 = &s.children[3].obj.children[0];
    assert!(std::rc::Rc::ptr_eq(metal, &r2.obj));
    assert_eq!(r2.name.as_deref(), Some("bsdf"));
    // The referenced declaration at scene level counts as consumed.
    for c in &s.children[1..] {
        c.mark_used();
    }
    s.check_unused().unwrap();
}

#[test]
fn nori_dialect() {
    let s = load(
        r#"<?xml version="1.0" encoding="utf-8"?>
<scene>
  <integrator type="path_mis">
    <integer name="maxDepth" value="5"/>
    <integer name="rrDepth" value="3"/>
  </integrator>
  <sampler type="independent">
    <integer name="sampleCount" value="16"/>
  </sampler>
  <camera type="perspective">
    <transform name="toWorld">
      <scale value="-1,1,1"/>
      <lookat target="0,0,0" origin="0,0,-4" up="0,1,0"/>
    </transform>
    <float name="fov" value="30"/>
    <integer name="width" value="64"/>
    <integer name="height" value="48"/>
  </camera>
  <mesh type="obj">
    <string name="filename" value="bunny.obj"/>
    <bsdf type="diffuse">
      <color name="albedo" value="0.5, 0.5, 0.5"/>
    </bsdf>
  </mesh>
  <mesh type="obj">
    <string name="filename" value="plane.obj"/>
    <bsdf type="diffuse">
      <texture type="checkerboard" name="albedo"/>
    </bsdf>
  </mesh>
  <mesh type="sphere">
    <bsdf type="dielectric">
      <float name="intIOR" value="1.5"/>
      <float name="extIOR" value="1"/>
      <color name="albedo" value="1"/>
    </bsdf>
  </mesh>
</scene>"#,
    );
    let kinds: Vec<Kind> = s.children.iter().map(|c| c.obj.kind).collect();
    assert_eq!(
        kinds,
        [
            Kind::Integrator,
            Kind::Sampler,
            Kind::Sensor,
            Kind::Shape,
            Kind::Shape,
            Kind::Shape
        ]
    );
    let integ = &s.children[0].obj;
    assert_eq!(integ.integer("max_depth", 0).unwrap(), 5);
    assert_eq!(integ.integer("rr_depth", 0).unwrap(), 3);
    assert_eq!(s.children[1].obj.integer("sample_count", 0).unwrap(), 16);
    let cam = &s.children[2].obj;
    assert!(cam.transform_opt("to_world").unwrap().is_some());
    assert_eq!(cam.integer("width", 0).unwrap(), 64);
    let bsdf = &s.children[3].obj.children[0].obj;
    assert_eq!(bsdf.rgb("reflectance", [0.0; 3]).unwrap(), [0.5; 3]);
    let bsdf2 = &s.children[4].obj.children[0].obj;
    assert!(bsdf2.child("reflectance").is_some());
    let diel = &s.children[5].obj.children[0].obj;
    assert_eq!(diel.float("int_ior", 0.0).unwrap(), 1.5);
    assert_eq!(diel.float("ext_ior", 0.0).unwrap(), 1.0);
    assert!(diel.has("albedo"), "albedo is only renamed on diffuse");
}

#[test]
fn nori_tests() {
    let s = load(
        r#"<scene>
  <test type="ttest">
    <string name="angles" value="0, 30, 60"/>
    <string name="references" value="1, 2"/>
    <bsdf type="diffuse"><color name="albedo" value="0.5"/></bsdf>
    <scene>
      <mesh type="sphere"/>
    </scene>
  </test>
  <test type="chi2test">
    <float name="significanceLevel" value="0.01"/>
    <bsdf type="microfacet"><float name="alpha" value="0.1"/></bsdf>
  </test>
</scene>"#,
    );
    let t = &s.children[0].obj;
    assert_eq!((t.kind, t.plugin.as_str()), (Kind::Test, "ttest"));
    assert_eq!(t.string("references", "").unwrap(), "1, 2");
    assert_eq!(t.children[1].obj.kind, Kind::Scene);
    assert_eq!(t.children[1].obj.children[0].obj.kind, Kind::Shape);
    let c = &s.children[1].obj;
    assert_eq!(c.float("significance_level", 0.0).unwrap(), 0.01);
}

#[test]
fn includes_splice_and_locate() {
    let d = temp_dir();
    std::fs::create_dir_all(d.join("sub")).unwrap();
    std::fs::write(
        d.join("sub/inc.xml"),
        "<scene version=\"3.0.0\">\n  <bsdf type=\"diffuse\" id=\"mat\"/>\n  <include filename=\"leaf.xml\"/>\n</scene>\n",
    )
    .unwrap();
    std::fs::write(
        d.join("sub/leaf.xml"),
        "<shape type=\"sphere\" id=\"$name\"/>",
    )
    .unwrap();
    std::fs::write(
        d.join("bad.xml"),
        "<scene>\n\n   <shape type=\"sphere\">\n     <float name=\"r\" value=\"x\"/>\n  </shape>\n</scene>",
    )
    .unwrap();
    let main = d.join("main.xml");
    let text = r#"<scene version="3.0.0">
  <default name="name" value="ball"/>
  <include filename="sub/inc.xml"/>
  <shape type="cube"><ref id="mat"/></shape>
  <shape type="cube"><ref id="ball" name="x"/></shape>
</scene>"#;
    std::fs::write(&main, text).unwrap();
    let s = load_file(&main, &[]).unwrap();
    assert_eq!(s.children.len(), 4);
    let bsdf = &s.children[0];
    assert_eq!(bsdf.obj.kind, Kind::Bsdf);
    assert_eq!(bsdf.loc.file.as_path(), d.join("sub/inc.xml"));
    assert_eq!((bsdf.loc.line, bsdf.loc.col), (2, 3));
    assert_eq!(s.children[1].obj.id.as_deref(), Some("ball"));
    assert!(std::rc::Rc::ptr_eq(
        &bsdf.obj,
        &s.children[2].obj.children[0].obj
    ));

    // Errors inside an included file carry its path and position.
    let with_bad = "<scene>\n  <include filename=\"bad.xml\"/>\n</scene>";
    let e = load_str(with_bad, &main, &[]).unwrap_err().to_string();
    let want = format!("{}:4:22: ", d.join("bad.xml").display());
    assert!(e.starts_with(&want), "{e}");

    // A missing include is reported at the <include>.
    let e = load_str(
        "<scene>\n <include filename=\"nope.xml\"/>\n</scene>",
        &main,
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with(&format!("{}:2:2: cannot include", main.display())),
        "{e}"
    );
    assert!(e.contains("cannot read file"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn include_of_single_object_and_cycles() {
    let d = temp_dir();
    std::fs::write(d.join("mat.xml"), "<bsdf type=\"diffuse\" name=\"bsdf\"/>").unwrap();
    std::fs::write(
        d.join("a.xml"),
        "<scene>\n<include filename=\"b.xml\"/>\n</scene>",
    )
    .unwrap();
    std::fs::write(
        d.join("b.xml"),
        "<scene>\n  <include filename=\"a.xml\"/>\n</scene>",
    )
    .unwrap();
    std::fs::write(
        d.join("self.xml"),
        "<scene><include filename=\"self.xml\"/></scene>",
    )
    .unwrap();
    let s = load_str(
        "<scene><shape type=\"sphere\"><include filename=\"mat.xml\"/></shape></scene>",
        &d.join("v.xml"),
        &[],
    )
    .unwrap();
    let c = &s.children[0].obj.children[0];
    assert_eq!(c.name.as_deref(), Some("bsdf"));

    let e = load_file(&d.join("a.xml"), &[]).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}:2:3: include cycle", d.join("b.xml").display())),
        "{e}"
    );
    let e = load_file(&d.join("self.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("include cycle"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn include_depth_limit() {
    let d = temp_dir();
    for i in 0..40 {
        std::fs::write(
            d.join(format!("n{i}.xml")),
            format!("<scene><include filename=\"n{}.xml\"/></scene>", i + 1),
        )
        .unwrap();
    }
    std::fs::write(d.join("n40.xml"), "<scene/>").unwrap();
    let e = load_file(&d.join("n0.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("deeper than"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn missing_file() {
    let p = std::env::temp_dir().join("tessera-definitely-missing-file.xml");
    let e = load_file(&p, &[]).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}: cannot read file: ", p.display())),
        "{e}"
    );
}

#[test]
fn structural_errors() {
    assert_err("<scene>\n  <foo/>\n</scene>", 2, 3, "unknown element <foo>");
    assert_err(
        "<scene>\n  <medium type=\"homogeneous\"/>\n</scene>",
        2,
        3,
        "unsupported element <medium>",
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
        "<scene>\n  <spectrum name=\"a\" value=\"400:0.1, 500:0.2\"/>\n</scene>",
        2,
        22,
        "spectra are not supported",
    );
    assert_err(
        "<scene>\n  <spectrum name=\"a\" value=\"0.1 0.2\"/>\n</scene>",
        2,
        22,
        "spectra are not supported",
    );
    assert_err(
        "<scene>\n  <spectrum name=\"a\" filename=\"x.spd\"/>\n</scene>",
        2,
        22,
        "spectra are not supported",
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
    assert_err(
        "<scene>\n  <shape type=\"sphere\"><ref id=\"m\"/></shape>\n  <bsdf type=\"diffuse\" id=\"m\"/>\n</scene>",
        2,
        24,
        "unknown id \"m\"",
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

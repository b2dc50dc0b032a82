//! End-to-end tests of the XML layer through [`load_str`] and [`load_file`].

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use tessera_core::math::Norm;

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
    assert!((o - DVec3::new(3.0, 2.0, -1.0)).norm() < 1e-12, "{o:?}");

    let b = sh.transform_opt("b").unwrap().unwrap();
    let p = b.transform_point3(DVec3::new(1.0, 1.0, 1.0));
    assert!((p - DVec3::new(7.0, 2.0, 2.0)).norm() < 1e-12, "{p:?}");

    let mm = sh.transform_opt("m").unwrap().unwrap();
    assert_eq!(mm.w_axis, DVec4::new(5.0, 6.0, 7.0, 1.0));

    // An axis of length 2 is used as given, as Mitsuba 3 does (see rotate.rs): +x goes to 2y.
    let rr = sh.transform_opt("r").unwrap().unwrap();
    let x = rr.transform_vector3(DVec3::X);
    assert!((x - 2.0 * DVec3::Y).norm() < 1e-12, "{x:?}");
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
    assert!((m2.z_axis.truncate() - DVec3::Z).norm() < 1e-12);
    assert!(m2.x_axis.truncate().dot(DVec3::Z).abs() < 1e-12);
    assert!((m2.x_axis.truncate().norm() - 1.0).abs() < 1e-12);
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
fn forward_refs_resolve_to_the_later_declaration() {
    let s = load(
        r#"<scene version="3.0.0">
  <shape type="sphere">
    <ref id="light"/>
    <ref id="white" name="bsdf"/>
  </shape>
  <bsdf type="diffuse" id="white"/>
  <emitter type="area" id="light"/>
</scene>"#,
    );
    let shape = &s.children[0].obj;
    let (white, light) = (&s.children[1].obj, &s.children[2].obj);
    assert!(std::rc::Rc::ptr_eq(&shape.children[0].obj, light));
    assert!(std::rc::Rc::ptr_eq(&shape.children[1].obj, white));
    assert!(shape.children[0].is_ref && light.is_referenced() && white.is_referenced());
    assert_eq!(shape.children[1].name.as_deref(), Some("bsdf"));
    assert_eq!(
        (shape.children[0].loc.line, shape.children[0].loc.col),
        (3, 5)
    );
    // Control: an id declared nowhere is still an error, at the reference.
    assert_err(
        "<scene>\n  <shape type=\"sphere\"><ref id=\"m\"/></shape>\n  <bsdf type=\"diffuse\" id=\"n\"/>\n</scene>",
        2,
        24,
        "unknown id \"m\" (no object is declared with it)",
    );
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

mod errors;
mod includes;
mod rotate;
mod search;
mod spectra;
mod upgrade;

//! Mitsuba 0.x files: Mitsuba 3's upgrade table, applied by each file's version.
use super::*;

const OLD: &str = r#"<scene version="0.6.0">
  <bsdf type="diffuse">
    <texture type="bitmap" name="diffuseReflectance">
      <string name="filename" value="t.png"/>
      <float name="uoffset" value="0.25"/>
      <float name="uscale" value="2"/>
      <integer name="vscale" value="4"/>
    </texture>
  </bsdf>
  <bsdf type="roughplastic">
    <rgb name="diffuseReflectance" value="0.5"/>
  </bsdf>
</scene>"#;

#[test]
fn old_files_are_upgraded() {
    let s = load(OLD);
    let diffuse = &s.children[0].obj;
    assert_eq!(diffuse.children[0].name.as_deref(), Some("reflectance"));
    let tex = &diffuse.children[0].obj;
    let names: Vec<&str> = tex.props.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["filename", "to_uv"]);
    let to_uv = tex.props.iter().find(|p| p.name == "to_uv").unwrap();
    // Located at the first of the parameters it replaces.
    assert_eq!((to_uv.loc.line, to_uv.loc.col), (5, 7));
    // uv' = scale * (uv + offset): (0, 0) -> (0.5, 0); (1, 1) -> (2.5, 4).
    let Value::Transform(m) = to_uv.value else {
        panic!("{:?}", to_uv.value)
    };
    assert!(m
        .transform_point3(DVec3::ZERO)
        .abs_diff_eq(DVec3::new(0.5, 0.0, 0.0), 1e-12));
    assert!(m
        .transform_point3(DVec3::ONE)
        .abs_diff_eq(DVec3::new(2.5, 4.0, 1.0), 1e-12));
    // Only a diffuse BSDF's diffuse_reflectance is renamed (as in Mitsuba).
    assert_eq!(s.children[1].obj.props[0].name, "diffuse_reflectance");
}

#[test]
fn control_new_files_are_not_upgraded() {
    let s = load(&OLD.replace("0.6.0", "3.0.0"));
    let diffuse = &s.children[0].obj;
    assert_eq!(
        diffuse.children[0].name.as_deref(),
        Some("diffuse_reflectance")
    );
    let names: Vec<&str> = diffuse.children[0]
        .obj
        .props
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(names, ["filename", "uoffset", "uscale", "vscale"]);
}

#[test]
fn the_version_is_each_files_own() {
    let d = temp_dir();
    std::fs::write(
        d.join("old.xml"),
        "<scene version=\"0.5.0\">\n  <bsdf type=\"diffuse\"><rgb name=\"diffuseReflectance\" value=\"0.5\"/></bsdf>\n</scene>",
    )
    .unwrap();
    let main = d.join("main.xml");
    let s = load_str(
        "<scene version=\"3.0.0\">\n  <include filename=\"old.xml\"/>\n  <bsdf type=\"diffuse\"><rgb name=\"diffuse_reflectance\" value=\"0.5\"/></bsdf>\n</scene>",
        &main,
        &[],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.children[0].obj.props[0].name, "reflectance");
    assert_eq!(s.children[1].obj.props[0].name, "diffuse_reflectance");
}

#[test]
fn upgrade_errors_are_located() {
    assert_err(
        "<scene version=\"0.6.0\">\n  <texture type=\"bitmap\">\n    <string name=\"uscale\" value=\"x\"/>\n  </texture>\n</scene>",
        3,
        5,
        "\"uscale\" must be a float, found string",
    );
    assert_err(
        "<scene version=\"0.6.0\">\n  <bsdf type=\"diffuse\">\n    <rgb name=\"reflectance\" value=\"1\"/>\n    <rgb name=\"diffuseReflectance\" value=\"1\"/>\n  </bsdf>\n</scene>",
        4,
        5,
        "parameter \"reflectance\" of bsdf \"diffuse\" is specified twice",
    );
}

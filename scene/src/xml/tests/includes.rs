//! Includes: splicing, location of errors inside included files, cycles, depth.
use super::*;

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

//! `<path>` and the file resolver: where includes and files named by objects are found.
use super::*;

/// A scene folder with `assets/frag.xml` (a bsdf), `assets/tex.png`, `sub/inc.xml` (a shape
/// naming `meshes/m.obj`) and `meshes/m.obj` beside the main file.
fn folder() -> PathBuf {
    let d = temp_dir();
    for sub in ["assets", "sub", "meshes"] {
        std::fs::create_dir_all(d.join(sub)).unwrap();
    }
    std::fs::write(
        d.join("assets/frag.xml"),
        "<bsdf type=\"diffuse\" id=\"m\"/>",
    )
    .unwrap();
    std::fs::write(d.join("assets/tex.png"), "").unwrap();
    std::fs::write(d.join("meshes/m.obj"), "").unwrap();
    std::fs::write(
        d.join("sub/inc.xml"),
        "<scene version=\"3.0.0\">\n  <shape type=\"obj\" id=\"s\"/>\n</scene>",
    )
    .unwrap();
    d
}

#[test]
fn path_folders_hold_includes_and_files() {
    let d = folder();
    let main = d.join("main.xml");
    let text = "<scene version=\"3.0.0\">\n  <path value=\"assets\"/>\n  <include filename=\"frag.xml\"/>\n  <include filename=\"sub/inc.xml\"/>\n</scene>";
    let s = load_str(text, &main, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        s.children[0].obj.loc.file.as_path(),
        d.join("assets/frag.xml")
    );
    // Files named by objects: the <path> folder, then the main file's folder (also for an
    // object declared in an included file in another folder), then beside the object's file.
    let bsdf = &s.children[0].obj;
    assert_eq!(bsdf.resolve_file("tex.png"), d.join("assets/tex.png"));
    let shape = &s.children[1].obj;
    assert_eq!(shape.resolve_file("meshes/m.obj"), d.join("meshes/m.obj"));
    assert_eq!(shape.resolve_file("inc.xml"), d.join("sub/inc.xml"));
    // Not found anywhere: the name beside the declaring file, for the error that follows.
    assert_eq!(shape.resolve_file("none.obj"), d.join("sub/none.obj"));

    // Control: without the <path>, the include is not found, and says where.
    let without = text.replace("  <path value=\"assets\"/>\n", "");
    let e = load_str(&without, &main, &[]).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}:2:3: cannot include", main.display())),
        "{e}"
    );
}

#[test]
fn a_path_in_an_included_file_ends_with_it() {
    let d = folder();
    std::fs::write(
        d.join("sub/paths.xml"),
        "<scene version=\"3.0.0\">\n  <path value=\"../assets\"/>\n  <include filename=\"frag.xml\"/>\n</scene>",
    )
    .unwrap();
    let main = d.join("main.xml");
    let s = load_str(
        "<scene version=\"3.0.0\">\n  <include filename=\"sub/paths.xml\"/>\n</scene>",
        &main,
        &[],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let found = std::fs::canonicalize(s.children[0].obj.loc.file.as_path()).unwrap();
    assert_eq!(
        found,
        std::fs::canonicalize(d.join("assets/frag.xml")).unwrap()
    );
    // Mitsuba drops an included file's <path>s when the include ends.
    let e = load_str(
        "<scene version=\"3.0.0\">\n  <include filename=\"sub/paths.xml\"/>\n  <include filename=\"frag.xml\"/>\n</scene>",
        &main,
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with(&format!("{}:3:3: cannot include", main.display())),
        "{e}"
    );
}

#[test]
fn path_errors_are_located() {
    let d = folder();
    let main = d.join("main.xml");
    let err = |text: &str| load_str(text, &main, &[]).unwrap_err().to_string();
    let at = |line: u32, col: u32| format!("{}:{line}:{col}: ", main.display());
    let e = err("<scene version=\"3.0.0\">\n  <path value=\"nowhere\"/>\n</scene>");
    assert!(
        e.starts_with(&at(2, 9)) && e.contains("folder") && e.contains("not found"),
        "{e}"
    );
    let e = err("<scene version=\"3.0.0\">\n  <path value=\"meshes/m.obj\"/>\n</scene>");
    assert!(e.starts_with(&at(2, 9)) && e.contains("not found"), "{e}");
    let e = err("<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n    <path value=\"assets\"/>\n  </shape>\n</scene>");
    assert!(
        e.starts_with(&at(3, 5)) && e.contains("only allowed at the top level"),
        "{e}"
    );
    let e = err("<scene version=\"3.0.0\">\n  <path/>\n</scene>");
    assert!(e.starts_with(&at(2, 3)) && e.contains("value"), "{e}");
    let e = err("<scene version=\"3.0.0\">\n  <path value=\"assets\" x=\"1\"/>\n</scene>");
    assert!(e.starts_with(&at(2, 24)), "{e}");
}

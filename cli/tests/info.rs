//! `tessera info`: what a scene holds, counted from the scene the renderer would render, and bad
//! input refused like `render` refuses it.
use std::path::Path;

use crate::support;
use support::{run, stderr};

fn scenes() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"))
}

fn row<'a>(out: &'a str, key: &str) -> &'a str {
    out.lines()
        .find_map(|l| l.trim_start().strip_prefix(key))
        .unwrap_or_else(|| panic!("no {key} row in {out}"))
        .trim()
}

#[test]
fn info_counts_what_the_material_scene_holds() {
    let o = run(&["info", scenes().join("materials.xml").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(row(&out, "image"), "256 x 256, 64 spp, seed 0");
    assert_eq!(row(&out, "camera"), "perspective");
    assert_eq!(
        row(&out, "primitives"),
        "4 triangles, 10 spheres, 0 disks; no instances"
    );
    assert!(
        row(&out, "shapes").starts_with("12: sphere 10, rectangle 2"),
        "{out}"
    );
    assert!(row(&out, "emitters").starts_with("2: "), "{out}");
    // The floor's 16x16 tiles (8-bit: 3 bytes a pixel and the codes' 3 KiB table) and the
    // checkerboard of the blend.
    assert_eq!(
        row(&out, "textures"),
        "1 image uses (1 distinct images, 3.8 KiB), 1 procedural"
    );
    assert_eq!(row(&out, "warnings"), "0");
}

#[test]
fn info_counts_a_shared_image_once_and_lists_warnings() {
    // One texture declared once and referenced from two BSDFs, and a third texture naming the
    // same file: one image in memory. The same file read raw is another image (the control).
    let dir = std::env::temp_dir().join(format!("tessera-info-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(scenes().join("textures/tiles.png"), dir.join("tiles.png")).unwrap();
    let bitmap = r#"<bsdf type="diffuse"><ref name="reflectance" id="tiles"/></bsdf>"#;
    let text = format!(
        r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="focus_distance" value="3"/></sensor>
  <texture type="bitmap" id="tiles"><string name="filename" value="tiles.png"/></texture>
  <shape type="sphere">{bitmap}</shape>
  <shape type="rectangle">{bitmap}</shape>
  <shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="tiles.png"/></texture></bsdf></shape>
  <shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="tiles.png"/><boolean name="raw" value="true"/></texture></bsdf></shape>
</scene>
"#
    );
    let scene = dir.join("two.xml");
    std::fs::write(&scene, text).unwrap();
    let o = run(&["info", scene.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(
        row(&out, "textures"),
        "4 image uses (2 distinct images, 7.5 KiB), 0 procedural"
    );
    assert_eq!(row(&out, "warnings"), "1");
    let located = format!("{}:2:", scene.display());
    assert!(
        out.contains(&located) && out.contains("focus_distance"),
        "{out}"
    );
    // Bad input: one located line, exit code 2, nothing on stdout.
    std::fs::write(
        &scene,
        "<scene version=\"3.0.0\">\n  <shape type=\"teapot\"/>\n</scene>\n",
    )
    .unwrap();
    let o = run(&["info", scene.to_str().unwrap()]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(e.contains(&format!("{}:2:3", scene.display())), "{e}");
    assert!(o.stdout.is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

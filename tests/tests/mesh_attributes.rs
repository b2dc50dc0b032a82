//! Mesh attributes (`mesh_attribute` textures over a PLY file's extra properties): the values
//! land on the mesh as the file holds them, named and grouped as Mitsuba 3 names them, a
//! polygon's face values cover every triangle of its fan, and every misuse is one located
//! error. Agreement of rendered images with Mitsuba 3.9.1 is in `real_agreement.rs` (three of
//! mitsuba-data's mesh-attribute scenes).
use std::path::{Path, PathBuf};
use tessera_core::geometry::{MeshAttribute, ShapeKind};
use tessera_scene::{load_scene_str, LoadedScene};
use tessera_tests::scenes_dir;

fn sphere_ply() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("real/mitsuba-data/tests/scenes/mesh_attributes/meshes/sphere_attribute.ply")
}

fn load(body: &str) -> Result<LoadedScene, String> {
    let xml = format!(
        r#"<scene version="3.0.0">
  <sensor type="perspective">
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  </sensor>
  {body}
</scene>"#
    );
    load_scene_str(&xml, &scenes_dir().join("attr-inputs.xml"), &[]).map_err(|e| e.to_string())
}

fn attributes(l: &LoadedScene) -> &[MeshAttribute] {
    match &l.scene.shapes[0].kind {
        ShapeKind::Mesh(m) => &m.attributes,
        _ => panic!("not a mesh"),
    }
}

/// The little-endian floats at `at` of `bytes`.
fn f32s(bytes: &[u8], at: usize, n: usize) -> Vec<f32> {
    (0..n)
        .map(|k| f32::from_le_bytes(bytes[at + 4 * k..at + 4 * k + 4].try_into().unwrap()))
        .collect()
}

/// The sphere's file read here on its own: after the header, 1192 vertices of 11 floats
/// (x y z nx ny nz u v color_0 color_1 color_2), then 528 faces of a count byte, three
/// 32-bit indices and four floats (color_0 color_1 color_2 weight_0).
#[test]
fn a_ply_files_attributes_are_its_values() {
    let path = sphere_ply();
    let bytes = std::fs::read(&path).unwrap();
    let end = b"end_header\n";
    let start = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
    let (nv, nf) = (1192, 528);
    let body = format!(
        r#"<shape type="ply"><string name="filename" value="{}"/></shape>"#,
        path.display()
    );
    let l = load(&body).expect("loads");
    let a = attributes(&l);
    let names: Vec<(&str, usize, bool)> = a
        .iter()
        .map(|a| (a.name.as_str(), a.dim, a.per_face))
        .collect();
    assert_eq!(
        names,
        [
            ("vertex_color", 3, false),
            ("face_color", 3, true),
            ("face_weight", 1, true)
        ]
    );
    for i in [0, 1, 600, nv - 1] {
        let rec = f32s(&bytes, start + i * 44, 11);
        assert_eq!(a[0].values[3 * i..3 * i + 3], rec[8..11], "vertex {i}");
    }
    let faces = start + nv * 44;
    for i in [0, 1, 300, nf - 1] {
        let rec = f32s(&bytes, faces + i * 29 + 13, 4);
        assert_eq!(bytes[faces + i * 29], 3, "face {i} is a triangle");
        assert_eq!(a[1].values[3 * i..3 * i + 3], rec[0..3], "face {i}");
        assert_eq!(a[2].values[i], rec[3], "face {i}");
    }
    assert_eq!(a[0].values.len(), 3 * nv);
    assert_eq!(a[2].values.len(), nf);
}

/// An ASCII file: integer `red green blue` become `vertex_color` as they are (Mitsuba does not
/// rescale them), and a quad's face value covers both triangles of its fan.
#[test]
fn named_colours_and_polygons() {
    let ply = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n\
               property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
               element face 2\nproperty list uchar int vertex_indices\nproperty float weight_0\n\
               end_header\n0 0 0 1 2 3\n1 0 0 4 5 6\n1 1 0 7 8 9\n0 1 0 10 11 12\n2 0 0 13 14 15\n\
               4 0 1 2 3 0.5\n3 1 4 2 0.25\n";
    let path = std::env::temp_dir().join(format!("tessera-attr-{}.ply", std::process::id()));
    std::fs::write(&path, ply).unwrap();
    let body = format!(
        r#"<shape type="ply"><string name="filename" value="{}"/></shape>"#,
        path.display()
    );
    let l = load(&body);
    std::fs::remove_file(&path).ok();
    let l = l.expect("loads");
    let a = attributes(&l);
    assert_eq!(a[0].name, "vertex_color");
    assert_eq!(a[0].values[..6], [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(a[1].name, "face_weight");
    assert_eq!(
        a[1].values,
        [0.5, 0.5, 0.25],
        "the quad's two triangles, then the triangle"
    );
}

fn refused(body: &str, needle: &str, line: u32) {
    let e = load(body).expect_err("must be refused");
    println!("{e}");
    assert!(e.contains(needle), "{e}");
    assert!(
        e.contains(&format!("attr-inputs.xml:{line}:")),
        "not located at line {line}: {e}"
    );
    assert_eq!(e.lines().count(), 1, "{e}");
}

#[test]
fn misuse_is_a_located_error() {
    let ply = sphere_ply();
    let ply = ply.display();
    let attr = |name: &str| {
        format!(
            r#"<texture type="mesh_attribute" name="reflectance"><string name="name" value="{name}"/></texture>"#
        )
    };
    // A name that is neither a vertex nor a face attribute.
    refused(
        &format!(
            "<shape type=\"sphere\"><bsdf type=\"diffuse\">\n{}</bsdf></shape>",
            attr("color")
        ),
        "must start with \"vertex_\" or \"face_\"",
        6,
    );
    // A shape without the attribute: a sphere, and a mesh that has others.
    refused(
        &format!(
            "<shape type=\"sphere\"><bsdf type=\"diffuse\">{}</bsdf></shape>",
            attr("vertex_color")
        ),
        "reads mesh attribute \"vertex_color\", which the shape does not have (it has none)",
        5,
    );
    refused(
        &format!(
            "<shape type=\"ply\"><string name=\"filename\" value=\"{ply}\"/><bsdf type=\"diffuse\">{}</bsdf></shape>",
            attr("vertex_weight")
        ),
        "(it has vertex_color, face_color, face_weight)",
        5,
    );
    // Where no triangle is given to the lookup: a light, a checkerboard.
    refused(
        &format!(
            "<shape type=\"ply\"><string name=\"filename\" value=\"{ply}\"/><emitter type=\"area\">\n<texture type=\"mesh_attribute\" name=\"radiance\"><string name=\"name\" value=\"vertex_color\"/></texture></emitter></shape>"
        ),
        "only BSDF parameters can read mesh attributes",
        6,
    );
    refused(
        &format!(
            "<shape type=\"ply\"><string name=\"filename\" value=\"{ply}\"/><bsdf type=\"diffuse\"><texture type=\"checkerboard\" name=\"reflectance\">\n<texture type=\"mesh_attribute\" name=\"color0\"><string name=\"name\" value=\"vertex_color\"/></texture></texture></bsdf></shape>"
        ),
        "only BSDF parameters can read mesh attributes",
        6,
    );
    // Control: the same BSDF on the mesh that has the attribute loads.
    load(&format!(
        "<shape type=\"ply\"><string name=\"filename\" value=\"{ply}\"/><bsdf type=\"diffuse\">{}</bsdf></shape>",
        attr("vertex_color")
    ))
    .expect("loads");
}

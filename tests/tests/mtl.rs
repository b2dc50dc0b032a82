//! OBJ files with MTL materials (`<shape type="obj">` with `use_mtl`): the file in `tests/mtl/`
//! is split into one shape per material, each material becomes the BSDF documented in
//! `scene/src/mesh/mtl_material.rs` (compared with the same tree written as scene XML), `Ke`
//! becomes an area light, `d` / `Tr` a mask that renders as partial transparency, and bad
//! material input is an error located in the OBJ or MTL file.
use std::path::{Path, PathBuf};

use glam::Vec3;
use tessera_core::bsdf::Bsdf;
use tessera_core::emitter::Emitter;
use tessera_scene::{load_scene_str, LoadedScene};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("mtl")
}

const SENSOR: &str = r#"<sensor type="perspective"><float name="fov" value="1"/>
    <transform name="to_world"><lookat origin="10.5, 0.5, 3" target="10.5, 0.5, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    </sensor>"#;

fn scene_in(folder: &Path, body: &str) -> Result<LoadedScene, String> {
    let xml = format!("<scene version=\"3.0.0\">\n{SENSOR}\n{body}\n</scene>");
    load_scene_str(&xml, &folder.join("scene.xml"), &[]).map_err(|e| e.to_string())
}

fn quads(extra: &str) -> LoadedScene {
    scene_in(
        &dir(),
        &format!(
            r#"<shape type="obj"><string name="filename" value="quads.obj"/>{extra}</shape>
            <emitter type="constant"><float name="radiance" value="1"/></emitter>"#
        ),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The first `<bsdf>` of a snippet, built as a scene would build it.
fn bsdf(xml: &str) -> Bsdf {
    let text = format!("<scene version=\"3.0.0\">{xml}</scene>");
    let root = tessera_scene::xml::load_str(&text, &dir().join("inline.xml"), &[]).unwrap();
    let c = root
        .children_of(tessera_scene::xml::Kind::Bsdf)
        .next()
        .unwrap();
    tessera_scene::build_bsdf_object(&c.obj).unwrap_or_else(|e| panic!("{e}"))
}

/// Asserts that two models agree (eval and pdf) over many direction pairs at several uv.
fn same(label: &str, a: &Bsdf, b: &Bsdf, scale: f32) {
    let mut rng = tessera_lab::stats::Pcg32::new(3);
    for _ in 0..500 {
        let wi = tessera_core::sampling::warp::square_to_uniform_sphere(rng.next_vec2());
        let wo = tessera_core::sampling::warp::square_to_uniform_sphere(rng.next_vec2());
        let uv = rng.next_vec2();
        let (fa, fb) = (a.eval(wi, wo, uv), b.eval(wi, wo, uv) * scale);
        let (pa, pb) = (a.pdf(wi, wo, uv), b.pdf(wi, wo, uv));
        let ok = (fa - fb).abs().max_element() <= 1e-5 * fa.max_element().max(1e-3)
            && (pa - pb).abs() <= 1e-5 * pa.max(1e-3);
        assert!(
            ok,
            "{label}: wi {wi} wo {wo} uv {uv}: {fa} / {pa} vs {fb} / {pb}"
        );
    }
}

#[test]
fn materials_map_onto_the_documented_trees() {
    let s = quads(r#"<boolean name="use_mtl" value="true"/>"#);
    let sc = &s.scene;
    // The faces without usemtl first, then each material in order of first use.
    assert_eq!(sc.shapes.len(), 6);
    let model = |i: usize| &sc.bsdfs[sc.shapes[i].bsdf as usize];
    same(
        "no material: the shape's default",
        model(0),
        &bsdf(r#"<bsdf type="diffuse"/>"#),
        1.0,
    );
    same(
        "matte (illum 1: Ks ignored)",
        model(1),
        &bsdf(r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.4, 0.6"/></bsdf>"#),
        1.0,
    );
    let kd = r#"<rgb name="reflectance" value="0.5, 0.3, 0.1"/>"#;
    let glossy = format!(
        r#"<bsdf type="mask"><float name="opacity" value="0.7"/>
          <bsdf type="blend"><float name="weight" value="0.3"/>
            <bsdf type="diffuse">{kd}</bsdf>
            <bsdf type="blend"><float name="weight" value="0.25"/>
              <bsdf type="blinnphong"><float name="shininess" value="80"/><float name="r0" value="0.04"/>
                <bsdf type="diffuse">{kd}</bsdf></bsdf>
              <bsdf type="blinnphong_metal"><float name="shininess" value="80"/><float name="r0" value="0.04"/>
                <rgb name="color" value="0.5, 0.3, 0.1"/></bsdf>
            </bsdf>
          </bsdf></bsdf>"#
    );
    same("glossy", model(2), &bsdf(&glossy), 1.0);
    same(
        "lamp",
        model(3),
        &bsdf(r#"<bsdf type="diffuse"><float name="reflectance" value="0.1"/></bsdf>"#),
        1.0,
    );
    same(
        "textured (map_Kd times Kd 0.5)",
        model(4),
        &bsdf(
            r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="../../scenes/textures/tess_rgb.png"/></texture></bsdf>"#,
        ),
        0.5,
    );
    same(
        "veil (Tr 0.6)",
        model(5),
        &bsdf(
            r#"<bsdf type="mask"><float name="opacity" value="0.4"/><bsdf type="diffuse"><float name="reflectance" value="0"/></bsdf></bsdf>"#,
        ),
        1.0,
    );
    // Ke: one area light, on the lamp's faces only; the constant environment is the other.
    let areas: Vec<_> = sc
        .emitters
        .iter()
        .filter_map(|e| match e {
            Emitter::Area(a) => Some(a),
            _ => None,
        })
        .collect();
    assert_eq!(areas.len(), 1);
    assert_eq!(areas[0].shape, 3);
    assert_eq!(areas[0].radiance, Vec3::new(4.0, 3.0, 2.0));
    assert_eq!(
        sc.shapes[3].emitter.map(|e| e as usize),
        sc.emitters
            .iter()
            .position(|e| matches!(e, Emitter::Area(_)))
    );
}

#[test]
fn without_use_mtl_the_file_is_one_plain_mesh_as_in_mitsuba() {
    let s = quads("");
    assert_eq!(s.scene.shapes.len(), 1);
    assert_eq!(s.scene.emitters.len(), 1, "only the environment");
    let b = &s.scene.bsdfs[s.scene.shapes[0].bsdf as usize];
    same("default", b, &bsdf(r#"<bsdf type="diffuse"/>"#), 1.0);
}

#[test]
fn emission_and_transparency_render() {
    let s = quads(r#"<boolean name="use_mtl" value="true"/>"#);
    // Looking straight at the veil (black, opacity 0.4) in front of a unit environment: 0.6.
    let fb = tessera_tests::render_loaded(&s, 20_000, 1);
    tessera_tests::assert_pixel_matches("veil", fb.at(0, 0), [0.6; 3], 1e-3);
    // Looking at the lamp: its radiance.
    let lamp_view = SENSOR
        .replace("10.5, 0.5, 3", "6.5, 0.5, 3")
        .replace("10.5, 0.5, 0", "6.5, 0.5, 0");
    let xml = format!(
        r#"<scene version="3.0.0">{lamp_view}<shape type="obj"><string name="filename" value="quads.obj"/><boolean name="use_mtl" value="true"/></shape></scene>"#
    );
    let s = load_scene_str(&xml, &dir().join("scene.xml"), &[]).unwrap();
    let fb = tessera_tests::render_loaded(&s, 64, 2);
    let p = fb.at(0, 0);
    let mean: Vec<f64> = p.sum.iter().map(|v| v / p.count as f64).collect();
    assert!(
        (mean[0] - 4.0).abs() < 1e-4
            && (mean[1] - 3.0).abs() < 1e-4
            && (mean[2] - 2.0).abs() < 1e-4,
        "{mean:?}"
    );
}

/// A folder with `files` written into it.
fn folder(tag: &str, files: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tessera_mtl_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    for (name, text) in files {
        std::fs::write(d.join(name), text).unwrap();
    }
    d
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn bad_material_input_is_located() {
    let shape = r#"<shape type="obj"><string name="filename" value="m.obj"/><boolean name="use_mtl" value="true"/></shape>"#;
    // (case name, files (name, text), expected location prefix, expected message part)
    type Case<'a> = (&'a str, Vec<(&'a str, String)>, &'a str, &'a str);
    let cases: Vec<Case> = vec![
        (
            "usemtl",
            vec![
                (
                    "m.obj",
                    format!("mtllib m.mtl\n{QUAD}usemtl nope\nf 1 2 3 4\n"),
                ),
                ("m.mtl", "newmtl red\nKd 1 0 0\n".into()),
            ],
            "m.obj:6:1: ",
            "usemtl \"nope\": no such material",
        ),
        (
            "lib",
            vec![(
                "m.obj",
                format!("{QUAD}  mtllib missing.mtl\nusemtl a\nf 1 2 3 4\n"),
            )],
            "m.obj:5:3: ",
            "mtllib \"missing.mtl\": cannot read material library",
        ),
        (
            "value",
            vec![
                (
                    "m.obj",
                    format!("mtllib m.mtl\n{QUAD}usemtl red\nf 1 2 3 4\n"),
                ),
                ("m.mtl", "newmtl red\n\nKd 1 0 0\nNs -3\n".into()),
            ],
            "m.mtl:4:1: ",
            "Ns of material \"red\" must be in [0, 1e6]",
        ),
        (
            "map",
            vec![
                (
                    "m.obj",
                    format!("mtllib m.mtl\n{QUAD}usemtl red\nf 1 2 3 4\n"),
                ),
                ("m.mtl", "newmtl red\nmap_Kd none.png\n".into()),
            ],
            "m.mtl:2:1: ",
            "none.png",
        ),
    ];
    for (tag, files, at, needle) in cases {
        let files: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
        let d = folder(tag, &files);
        let e = scene_in(&d, shape)
            .err()
            .unwrap_or_else(|| panic!("{tag}: loaded"));
        std::fs::remove_dir_all(&d).ok();
        assert!(e.contains(at) && e.contains(needle), "{tag}: {e}");
    }
}

#[test]
fn shape_level_bsdf_needs_faces_without_material() {
    let d = folder(
        "all",
        &[
            (
                "m.obj",
                &format!("mtllib m.mtl\n{QUAD}usemtl red\nf 1 2 3 4\n"),
            ),
            ("m.mtl", "newmtl red\nKd 1 0 0\n"),
            (
                "m.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                 property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                 end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            ),
        ],
    );
    let body = r#"<shape type="obj"><string name="filename" value="m.obj"/><boolean name="use_mtl" value="true"/>
        <bsdf type="diffuse"/></shape>"#;
    let e = scene_in(&d, body).expect_err("an error");
    assert!(
        e.contains("scene.xml:7:9: ") && e.contains("would apply to nothing"),
        "{e}"
    );
    // use_mtl is an OBJ parameter only.
    let e = scene_in(
        &d,
        r#"<shape type="ply"><string name="filename" value="m.ply"/><boolean name="use_mtl" value="true"/></shape>"#,
    )
    .expect_err("an error");
    assert!(e.contains("unused parameter \"use_mtl\""), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

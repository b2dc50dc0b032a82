//! Wakame's conventions: the same Nori-vocabulary file, read as Wakame reads it, gives the rays
//! Wakame's perspective camera gives, and read as Nori reads it, Nori's.
//!
//! The oracle is each camera's published mapping from a film position `(u, v)` in `[0,1]^2`
//! (top-left origin) to a direction in camera space, with `c = 1 / tan(fov_x / 2)` and `a` the
//! aspect ratio width / height:
//! - Nori (scale `(-1/2, -a/2)`, translate `(-1, -1/a)` before the projection):
//!   `((1 - 2u) / c, (1 - 2v) / (a c), 1)`;
//! - Wakame (scale `(+1/2, -a/2)`, translate `(+1, -1/a)`): `((2u - 1) / c, (1 - 2v) / (a c), 1)`.
//!
//! Each is checked over a grid of film positions, with the other's mapping as the control that
//! must fail. How a file or the command line chooses the conventions is checked too.
use glam::{Vec2, Vec3};
use std::path::Path;
use tessera_core::math::Norm;
use tessera_scene::{load_scene_as, load_scene_str, Dialect, LoadedScene};

const WIDTH: u32 = 40;
const HEIGHT: u32 = 24;
const FOV_X: f32 = 50.0;

/// A Nori-vocabulary file with an asymmetric view, optionally carrying a dialect instruction.
fn scene(instruction: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
{instruction}
<scene>
  <integrator type="normals"/>
  <camera type="perspective">
    <transform name="toWorld"><lookat origin="3, 2, 5" target="0.5, 0, 0" up="0, 1, 0"/></transform>
    <float name="fov" value="{FOV_X}"/>
    <integer name="width" value="{WIDTH}"/>
    <integer name="height" value="{HEIGHT}"/>
  </camera>
  <mesh type="obj"><string name="filename" value="meshes/cbox_floor.obj"/></mesh>
</scene>
"#
    )
}

fn load(text: &str) -> LoadedScene {
    let path = tessera_tests::scenes_dir().join("inline-test.xml");
    load_scene_str(text, &path, &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// The camera-space direction each renderer's mapping gives at film position `(u, v)`.
fn oracle(dialect: Dialect, u: f32, v: f32) -> Vec3 {
    let c = 1.0 / (FOV_X.to_radians() / 2.0).tan();
    let a = WIDTH as f32 / HEIGHT as f32;
    let x = match dialect {
        Dialect::Nori => (1.0 - 2.0 * u) / c,
        Dialect::Wakame => (2.0 * u - 1.0) / c,
    };
    Vec3::new(x, (1.0 - 2.0 * v) / (a * c), 1.0).unit()
}

/// The sine of the largest angle between the loaded camera's rays and the oracle's, over a grid
/// of film positions. The camera's placement is the file's, as read with Nori's conventions
/// (`reference`), so that only the film mapping is under test.
fn worst_angle(loaded: &LoadedScene, reference: &LoadedScene, dialect: Dialect) -> f32 {
    let cam = &loaded.scene.camera;
    let to_world = reference.scene.camera.to_world;
    let mut worst = 0.0f32;
    for i in 0..=8 {
        for j in 0..=8 {
            let (u, v) = (i as f32 / 8.0, j as f32 / 8.0);
            let ray = cam.generate_ray(Vec2::new(u * WIDTH as f32, v * HEIGHT as f32));
            let want = to_world.vector(oracle(dialect, u, v)).unit();
            let sin = ray.d.cross(want).norm();
            worst = worst.max(if ray.d.dot(want) > 0.0 { sin } else { 2.0 });
        }
    }
    worst
}

#[test]
fn each_dialect_gives_its_renderers_rays() {
    let nori = load(&scene(""));
    let wakame = load(&scene(r#"<?tessera dialect="wakame"?>"#));
    assert_eq!(
        (nori.dialect, wakame.dialect),
        (Dialect::Nori, Dialect::Wakame)
    );
    let tol = 1e-5;
    assert!(worst_angle(&nori, &nori, Dialect::Nori) < tol);
    assert!(worst_angle(&wakame, &nori, Dialect::Wakame) < tol);
    // Controls: each renderer's rays are not the other's (the view is not symmetric).
    assert!(worst_angle(&nori, &nori, Dialect::Wakame) > 0.1);
    assert!(worst_angle(&wakame, &nori, Dialect::Nori) > 0.1);
    // The camera stays where it was: only the film's x axis turns over.
    let (a, b) = (nori.scene.camera.to_world, wakame.scene.camera.to_world);
    assert_eq!(a.point(Vec3::ZERO), b.point(Vec3::ZERO));
}

#[test]
fn the_command_line_dialect_overrides_the_files() {
    let dir = std::env::temp_dir().join(format!("tessera-dialect-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let meshes = tessera_tests::scenes_dir().join("meshes");
    let text = scene(r#"<?tessera dialect="wakame"?>"#)
        .replace("meshes/", &format!("{}/", meshes.display()));
    let file = dir.join("wakame.xml");
    std::fs::write(&file, &text).unwrap();
    let declared = load_scene_as(&file, &[], None).unwrap();
    let as_nori = load_scene_as(&file, &[], Some(Dialect::Nori)).unwrap();
    let as_wakame = load_scene_as(&file, &[], Some(Dialect::Wakame)).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(declared.dialect, Dialect::Wakame);
    assert_eq!(as_nori.dialect, Dialect::Nori);
    assert_eq!(as_wakame.dialect, Dialect::Wakame);
    // A dialect chosen on the command line is part of the scene's identity (checkpoints and
    // part files compare it); one the file declares is in its bytes already.
    assert_ne!(declared.source_hash, as_nori.source_hash);
    assert_ne!(as_nori.source_hash, as_wakame.source_hash);
}

#[test]
fn bad_instructions_are_located_errors() {
    let path = Path::new("/nowhere/s.xml");
    for (instruction, says) in [
        (
            r#"<?tessera dialect="mitsuba0"?>"#,
            "unknown dialect \"mitsuba0\"",
        ),
        (
            r#"<?tessera flavour="wakame"?>"#,
            "expected <?tessera dialect=",
        ),
        (
            r#"<?tessera dialect="nori"?><?tessera dialect="wakame"?>"#,
            "a second <?tessera dialect",
        ),
    ] {
        let err = load_scene_str(&scene(instruction), path, &[])
            .err()
            .unwrap_or_else(|| panic!("{instruction} was accepted"))
            .to_string();
        assert!(err.starts_with("/nowhere/s.xml:2:"), "{err}");
        assert!(err.contains(says), "{err}");
    }
    // Other processing instructions are none of Tessera's business.
    load(&scene(r#"<?xml-stylesheet href="x.css"?>"#));
}

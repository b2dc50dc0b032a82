//! Real public scene files (tests/real/, listed in tests/real/MANIFEST) load through the same
//! loader `tessera render` uses, with no error. Each source folder keeps its notice and
//! license; `scripts/real_scenes_survey.py` measures the wider set these come from.
use std::path::{Path, PathBuf};

use tessera_scene::{load_scene, load_scene_str};

/// The corpus folder.
fn real_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("real")
}

/// A `name=value` define of a list line.
fn define(word: &str) -> (String, String) {
    let (k, v) = word
        .split_once('=')
        .unwrap_or_else(|| panic!("{word:?} is not name=value"));
    (k.to_string(), v.to_string())
}

/// The scene paths the manifest lists, each with the defines it is loaded with (comments and
/// blank lines skipped).
fn manifest() -> Vec<(PathBuf, Vec<(String, String)>)> {
    let text = std::fs::read_to_string(real_dir().join("MANIFEST")).expect("tests/real/MANIFEST");
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| {
            let mut words = l.split_whitespace();
            let path = real_dir().join(words.next().expect("a path"));
            (path, words.map(define).collect())
        })
        .collect()
}

/// Loads `text` as if it were the file at `path` and returns the one-line error.
fn error_of(text: &str, path: &Path) -> String {
    match load_scene_str(text, path, &[]) {
        Ok(_) => panic!("{} loaded, but it should not", path.display()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn every_listed_real_scene_loads() {
    let scenes = manifest();
    assert!(
        scenes.len() >= 15,
        "the manifest lists {} scenes",
        scenes.len()
    );
    let mut failures = Vec::new();
    for (path, defines) in &scenes {
        if let Err(e) = load_scene(path, defines) {
            failures.push(e.to_string());
        }
    }
    assert!(
        failures.is_empty(),
        "{} failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn control_an_unsupported_construct_fails_located() {
    // A listed scene with an emitter Tessera does not read added fails at it.
    let path = real_dir().join("mitsuba-data/docs/scenes/integrator_depth_1.xml");
    let text = std::fs::read_to_string(&path).unwrap();
    let with_medium = text.replacen(
        "    <default name=\"spp\"",
        "    <emitter type=\"sunsky\" id=\"sky\"></emitter>\n    <default name=\"spp\"",
        1,
    );
    assert_ne!(with_medium, text);
    let e = error_of(&with_medium, &path);
    let want = format!(
        "{}:4:5: Mitsuba 3's emitter \"sunsky\", which Tessera does not read yet",
        path.display()
    );
    assert!(e.starts_with(&want), "{e}");
    assert!(!e.contains('\n'), "{e}");
}

#[test]
fn control_the_scenes_need_what_they_exercise() {
    // Without its <path>, the meshes in ../../common are not found (at the first one).
    let path = real_dir().join("mitsuba-data/docs/scenes/integrator_depth_1.xml");
    let text = std::fs::read_to_string(&path).unwrap();
    let e = error_of(
        &text.replacen("<path value=\"../../common\"/>", "", 1),
        &path,
    );
    assert!(e.starts_with(&format!("{}:", path.display())), "{e}");
    assert!(
        e.contains("meshes/cbox/") && e.contains("cannot read mesh"),
        "{e}"
    );

    // cbox-rgb.xml declares the area emitter after fragments/shapes.xml refers to it; with
    // another id, the reference in the included file is reported where it is.
    let path = real_dir().join("mitsuba-data/scenes/cbox/cbox-rgb.xml");
    let text = std::fs::read_to_string(&path).unwrap();
    let e = error_of(&text.replace("id=\"area-emitter\"", "id=\"other\""), &path);
    let shapes = real_dir().join("mitsuba-data/scenes/cbox/fragments/shapes.xml");
    let want = format!("{}:9:9: unknown id \"area-emitter\"", shapes.display());
    assert!(e.starts_with(&want), "{e}");
}

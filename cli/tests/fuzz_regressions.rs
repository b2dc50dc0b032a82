//! The fuzz targets' checks (`fuzz/fuzz_targets/`), replayed with the stable toolchain on every
//! input that once crashed a loader (`tests/fixtures/fuzz/<target>/`) and on the fuzz seed
//! corpora (`fuzz/corpus/<target>/`): no panic, errors on one line, loaded meshes valid, pixel
//! means finite. Crash inputs are also checked against the message they must now give.
use std::path::{Path, PathBuf};
use tessera_core::film::PixelAccum;
use tessera_core::render::RenderJob;

#[path = "../../fuzz/fuzz_targets/common.rs"]
mod common;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The files of `dir`, sorted (none if it does not exist).
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.map(|e| e.unwrap().path()).collect())
        .unwrap_or_default();
    v.sort();
    v
}

/// The crash inputs and seeds of `target`.
fn inputs(target: &str) -> Vec<PathBuf> {
    let mut v = files(&root().join("tests/fixtures/fuzz").join(target));
    v.extend(files(&root().join("../fuzz/corpus").join(target)));
    assert!(!v.is_empty(), "no inputs for {target}");
    v
}

/// What a crash input must give now: `Ok` for `None`, else an error containing the text.
fn expected(file: &Path) -> Option<Option<&'static str>> {
    let name = file.file_name()?.to_str()?;
    REGRESSIONS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, want)| *want)
}

/// Crash inputs (file name under `tests/fixtures/fuzz/<target>/`) and the error each must give
/// now (`None`: it loads).
const REGRESSIONS: &[(&str, Option<&str>)] = &[];

/// Checks an outcome against the expectation for `file`, if it is a crash input.
fn check(file: &Path, outcome: Result<(), String>) {
    if let Err(e) = &outcome {
        assert!(
            !e.contains('\n'),
            "{}: multi-line error {e:?}",
            file.display()
        );
    }
    match (expected(file), &outcome) {
        (None, _) | (Some(None), Ok(())) => {}
        (Some(Some(want)), Err(e)) if e.contains(want) => {}
        (Some(want), got) => panic!("{}: want {want:?}, got {got:?}", file.display()),
    }
}

#[test]
fn xml_scene_inputs() {
    for file in inputs("xml_scene") {
        let bytes = std::fs::read(&file).unwrap();
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue;
        };
        let path = common::dir().join("scene.xml");
        let outcome = tessera_scene::load_scene_str(text, &path, &[]).map(|loaded| {
            let (w, h) = (loaded.scene.camera.width, loaded.scene.camera.height);
            for (x, y) in [(0, 0), (w / 2, h / 2), (w - 1, h - 1)] {
                let mut acc = PixelAccum::default();
                let (scene, integrator) = (&loaded.scene, &loaded.integrator);
                RenderJob::new(scene, integrator, loaded.seed).accumulate(x, y, 0..1, &mut acc);
                assert!(
                    acc.mean().iter().all(|c| c.is_finite()),
                    "{}: non-finite pixel",
                    file.display()
                );
            }
        });
        check(&file, outcome.map_err(|e| e.to_string()));
    }
}

#[test]
fn obj_inputs() {
    for file in inputs("obj") {
        let path = common::put("input.obj", &std::fs::read(&file).unwrap());
        let plain = tessera_scene::mesh::load_obj(&path).map(|m| vec![m]);
        let split = tessera_scene::mesh::load_obj_with_materials(&path).map(|p| {
            let by = p.by_material.into_iter().map(|x| x.1);
            p.plain.into_iter().chain(by).collect::<Vec<_>>()
        });
        for r in [plain, split] {
            let outcome = r.map(|meshes| {
                for m in meshes {
                    m.validate(&path).expect("a loaded mesh validates");
                }
            });
            check(&file, outcome.map_err(|e| e.to_string()));
        }
    }
}

#[test]
fn ply_inputs() {
    for file in inputs("ply") {
        let path = common::put("input.ply", &std::fs::read(&file).unwrap());
        let outcome = tessera_scene::mesh::load_ply(&path)
            .map(|m| m.validate(&path).expect("a loaded mesh validates"));
        check(&file, outcome.map_err(|e| e.to_string()));
    }
}

#[test]
fn checkpoint_inputs() {
    for file in inputs("checkpoint") {
        let bytes = std::fs::read(&file).unwrap();
        let outcome = tessera::checkpoint::read_checkpoint(&bytes).map(|c| {
            let n = c.meta.width as usize * c.meta.height as usize;
            assert_eq!(c.pixels.len(), n, "{}", file.display());
        });
        check(&file, outcome);
        // Every seed is a valid checkpoint; a truncated copy must be refused on one line.
        let cut = tessera::checkpoint::read_checkpoint(&bytes[..bytes.len() / 2]);
        check(
            &file,
            cut.map(|_| panic!("{}: half a checkpoint was read", file.display())),
        );
    }
}

//! `tessera test` on our own Nori-style test files (`test-lambert.xml`, `test-lights.xml`;
//! references computed independently by scripts/make_ttest_files.py), and a control that a
//! wrong reference fails.
use std::path::Path;
use tessera_lab::testfile::run_test_object;

fn file() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test-lambert.xml")
}

/// Runs the test file at `path` (under `tests/`) and asserts that it has `cases` cases and that
/// every one passes, listing the failures.
fn assert_test_file_passes(path: &Path, cases: usize) {
    let root = tessera_scene::xml::load_file(path, &[]).expect("test file loads");
    let results = run_test_object(&root, 0, |_| {}).expect("test file runs");
    assert_eq!(results.len(), cases);
    let failed: Vec<String> = results
        .iter()
        .filter(|r| !r.passed)
        .map(|r| {
            format!(
                "{} ({:.6} vs {:.6}, {})",
                r.label, r.mean, r.reference, r.test
            )
        })
        .collect();
    assert!(failed.is_empty(), "failed cases: {failed:#?}");
}

#[test]
fn lambert_point_and_furnace_test_file_passes() {
    assert_test_file_passes(&file(), 29);
}

/// Spot, directional, distant disk (straight and tilted), constant and envmap lights over the
/// same floor, each with every integrator that can see it (scripts/make_ttest_files.py).
#[test]
fn lights_test_file_passes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test-lights.xml");
    assert_test_file_passes(&path, 42);
}

#[test]
fn a_reference_two_percent_off_fails() {
    let text = std::fs::read_to_string(file()).unwrap();
    let start = text.find("value=\"").unwrap() + 7;
    let end = start + text[start..].find(',').unwrap();
    let wrong = text[start..end].parse::<f64>().unwrap() * 1.02;
    let altered = format!("{}{wrong}{}", &text[..start], &text[end..]);
    let root = tessera_scene::xml::load_str(&altered, &file(), &[]).expect("altered file loads");
    let results = run_test_object(&root, 0, |_| {}).expect("runs");
    assert!(
        !results[0].passed,
        "a 2% wrong reference passed: {:?}",
        results[0].test
    );
}

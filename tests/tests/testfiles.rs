//! `tessera test` on our own Nori-style test files (`test-lambert.xml`, `test-lights.xml`;
//! references computed independently by scripts/make_ttest_files.py), and a control that a
//! wrong reference fails.
use std::path::Path;
use tessera_lab::testfile::run_test_object;

fn file() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test-lambert.xml")
}

#[test]
fn lambert_point_and_furnace_test_file_passes() {
    let root = tessera_scene::xml::load_file(&file(), &[]).expect("test file loads");
    let results = run_test_object(&root, 0, |_| {}).expect("test file runs");
    assert_eq!(results.len(), 29);
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

/// Spot, directional, distant disk (straight and tilted), constant and envmap lights over the
/// same floor, each with every integrator that can see it (scripts/make_ttest_files.py).
#[test]
fn lights_test_file_passes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/test-lights.xml");
    let root = tessera_scene::xml::load_file(&path, &[]).expect("test file loads");
    let results = run_test_object(&root, 0, |_| {}).expect("test file runs");
    assert_eq!(results.len(), 42);
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

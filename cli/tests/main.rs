//! The command line's end-to-end tests, in one test binary (one link of the workspace instead of
//! one per file). Each file beside this one is a module named after it (`cargo test --release -p
//! tessera-cli --test cli adaptive::` runs one file's tests); `every_file_is_a_module`
//! fails when a file here is missing from the list below. `support/` and `scenes/` are shared
//! helpers.

mod adaptive;
mod adaptive_reuse;
mod aov;
mod api;
mod bench;
mod bench_fresh;
mod cli_errors;
mod compare;
mod determinism;
mod fuzz_regressions;
mod info;
mod limits;
mod overlay;
mod probe;
mod progressive;
mod reuse;
mod sampler_cli;
mod scenes;
mod split_merge;
mod support;
mod target_error;
mod view_cli;

/// Cargo builds only this file's modules (`autotests = false`), so a test file left out of the
/// list above would never run: fail instead.
#[test]
fn every_file_is_a_module() {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let listed = include_str!("main.rs");
    for entry in std::fs::read_dir(&here).unwrap() {
        let path = entry.unwrap().path();
        let (Some(stem), Some("rs")) = (
            path.file_stem().and_then(|s| s.to_str()),
            path.extension().and_then(|e| e.to_str()),
        ) else {
            continue;
        };
        if stem != "main" {
            assert!(
                listed.contains(&format!("\nmod {stem};\n")),
                "{} is not a module of {}: add `mod {stem};`",
                path.display(),
                here.join("main.rs").display()
            );
        }
    }
}

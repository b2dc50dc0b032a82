//! Keeps every crate's files layered: `scripts/import_cycles.py` finds no cycle among the files
//! of any crate of the workspace (a file should be readable knowing only the files below it;
//! a doc link counts as a use). Control: the script flags two made-up files that use each
//! other, so a checker that cannot fail is caught.
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Runs the script on `src`; its exit status and its report.
fn cycles(src: &Path) -> (Option<i32>, String) {
    let out = Command::new("python3")
        .arg(root().join("scripts/import_cycles.py"))
        .arg(src)
        .output()
        .expect("python3 runs scripts/import_cycles.py");
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code(), text)
}

#[test]
fn no_crate_has_an_import_cycle() {
    let mut crates: Vec<PathBuf> = std::fs::read_dir(root())
        .unwrap()
        .map(|e| e.unwrap().path().join("src"))
        .filter(|src| src.join("lib.rs").exists() || src.join("main.rs").exists())
        .collect();
    crates.sort();
    assert!(crates.len() >= 5, "crates found: {crates:?}");
    for src in &crates {
        let (code, text) = cycles(src);
        assert_eq!(code, Some(0), "{}:\n{text}", src.display());
    }

    // Control: two files that name each other's items.
    let dir = std::env::temp_dir().join(format!("tessera-layering-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("lib.rs"), "mod a;\nmod b;\n").unwrap();
    std::fs::write(dir.join("a.rs"), "use crate::b::B;\npub struct A(B);\n").unwrap();
    std::fs::write(
        dir.join("b.rs"),
        "/// See [`crate::a::A`].\npub struct B;\n",
    )
    .unwrap();
    let (code, text) = cycles(&dir);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(
        code,
        Some(1),
        "control: the cycle a.rs <-> b.rs was not found:\n{text}"
    );
}

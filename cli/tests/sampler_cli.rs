//! `--sampler` on `tessera render` and `tessera bench`: an unknown name is a one-line error with
//! exit code 2; `tessera bench --sampler independent,zsobol` measures both in one report, the
//! `sampler` column naming each.
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tessera_lab::bench::read_csv;

const BIN: &str = env!("CARGO_BIN_EXE_tessera");

/// Runs `tessera SUB scenes/cbox.xml -D res=8 ARGS...`.
fn on_cbox(sub: &str, args: &[&str]) -> Output {
    Command::new(BIN)
        .arg(sub)
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml"))
        .args(["-D", "res=8"])
        .args(args)
        .output()
        .unwrap()
}

/// A path of the test's temporary folder as text.
fn text(p: &Path) -> &str {
    p.to_str().expect("temporary paths are UTF-8")
}

fn tmp(name: &str) -> PathBuf {
    let p = std::env::temp_dir().join(format!("tessera-sampler-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&p);
    std::fs::create_dir_all(&p).unwrap();
    p
}

#[test]
fn unknown_sampler_is_a_usage_error() {
    let dir = tmp("unknown");
    let out = dir.join("o.exr");
    let o = on_cbox("render", &["--sampler", "sobolx", "-o", text(&out)]);
    assert_unknown(&o);
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

fn assert_unknown(o: &std::process::Output) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("unknown sampler \"sobolx\""), "{err}");
}

#[test]
fn bench_measures_both_samplers_in_one_report() {
    let dir = tmp("bench");
    let reference = dir.join("ref.exr");
    let o = on_cbox(
        "render",
        &[
            "-D",
            "rfilter=box",
            "--spp",
            "16",
            "--quiet",
            "--sampler",
            "zsobol",
            "-o",
            text(&reference),
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = dir.join("r.csv");
    let o = on_cbox(
        "bench",
        &[
            "--waves",
            "-D",
            "rfilter=box",
            "--max-spp",
            "4",
            "--quiet",
            "--sampler",
            "independent,zsobol",
            "--reference",
            text(&reference),
            "-o",
            text(&csv),
        ],
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("path (zsobol)"), "{stdout}");
    let rows = read_csv(&csv).unwrap();
    let samplers: Vec<(&str, u64)> = rows.iter().map(|r| (r.sampler.as_str(), r.spp)).collect();
    assert_eq!(
        samplers,
        [
            ("independent", 1),
            ("independent", 2),
            ("independent", 4),
            ("zsobol", 1),
            ("zsobol", 2),
            ("zsobol", 4)
        ]
    );
    // An unknown name is refused before anything is measured.
    let bad = dir.join("bad.csv");
    let o = on_cbox(
        "bench",
        &[
            "--sampler",
            "zsobol,sobolx",
            "--reference",
            text(&reference),
            "-o",
            text(&bad),
        ],
    );
    assert_unknown(&o);
    assert!(!bad.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

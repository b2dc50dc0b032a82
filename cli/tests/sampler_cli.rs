//! `--sampler` on `tessera render` and `tessera bench`: an unknown name is a one-line error with
//! exit code 2; `tessera bench --sampler independent,zsobol` measures both in one report, the
//! `sampler` column naming each; `tessera render` sets zsobol's pixel blocks from `--spp`, and a
//! resumed render keeps those of its first run.
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

/// `tessera render cbox -D res=8 -D rfilter=box --sampler zsobol -q ARGS -o OUT`, checked to
/// succeed; returns OUT's pixels.
fn zsobol_render(dir: &Path, name: &str, args: &[&str]) -> Vec<[f32; 3]> {
    let out = dir.join(name);
    let mut a = vec!["-D", "rfilter=box", "--sampler", "zsobol", "-q"];
    a.extend_from_slice(args);
    a.extend_from_slice(&["-o", text(&out)]);
    let o = on_cbox("render", &a);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    match name.ends_with(".pfm") {
        true => tessera::image_io::read_image(&out).unwrap().data,
        false => Vec::new(),
    }
}

/// zsobol's pixel blocks follow `--spp` (the file's `sample_count` is 64): `--spp 8` gives the
/// bits of the file set to 8 samples, and so do sample-range parts told `--spp 8`, merged; a
/// render resumed to 8 samples from a checkpoint of 4 keeps the first run's blocks of 4, as an
/// 8-sample render of blocks of 4 made in process. Controls: parts not told `--spp` draw from
/// the file's blocks of 64 and give other bits; so does the resumed render against `--spp 8`.
#[test]
fn zsobol_blocks_follow_spp_and_resumes_keep_them() {
    let dir = tmp("blocks");
    let spp8 = zsobol_render(&dir, "a.pfm", &["--spp", "8"]);
    assert_eq!(spp8, zsobol_render(&dir, "b.pfm", &["-D", "spp=8"]));
    let merged = |name: &str, told: &[&str]| {
        let parts = ["0..3", "3..8"].map(|r| {
            let mut a = vec!["--sample-range", r];
            a.extend_from_slice(told);
            zsobol_render(&dir, &format!("{name}{r}.exr"), &a);
            text(&dir.join(format!("{name}{r}.exr"))).to_string()
        });
        let out = dir.join(format!("{name}.pfm"));
        let o = Command::new(BIN)
            .args(["merge", "-q", &parts[0], &parts[1], "-o", text(&out)])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        tessera::image_io::read_image(&out).unwrap().data
    };
    assert_eq!(merged("told", &["--spp", "8"]), spp8);
    assert_ne!(merged("untold", &[]), spp8, "control: blocks of 64");

    let ck = dir.join("c.ckpt");
    zsobol_render(&dir, "four.exr", &["--spp", "4", "--checkpoint", text(&ck)]);
    let resumed = zsobol_render(&dir, "r.pfm", &["--resume", text(&ck), "--spp", "8"]);
    let mut l = tessera_scene::load_scene(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml"),
        &[("res", "8"), ("rfilter", "box")].map(|(k, v)| (k.to_string(), v.to_string())),
    )
    .unwrap();
    l.set_sampler(Some("zsobol"), 4).unwrap();
    let job = tessera_core::render::RenderJob::new(&l.scene, &l.integrator, l.seed);
    let opts = tessera::render::RenderOptions::default();
    let blocks_of_4 = tessera::render::render(&job, 0..8, &opts, &mut |_, _| {}).rgb();
    assert_eq!(resumed, blocks_of_4);
    assert_ne!(
        resumed, spp8,
        "control: the resumed render's blocks are not --spp's"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

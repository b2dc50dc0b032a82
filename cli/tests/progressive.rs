//! Progressive rendering, interrupts and checkpoints: a render stopped by SIGINT, SIGTERM or
//! SIGKILL and resumed (several times) gives the same bits as one uninterrupted render of the
//! same total spp; a checkpoint from another scene, seed, size or integrator, or a damaged one,
//! is refused with exit 2 and one line; `--time` stops on its own.
//!
//! The scene is `scenes/cbox.xml` at 12x12 pixels with 4-pixel tiles (9 tiles, so a stop at a
//! tile boundary leaves pixels at different counts). The uninterrupted reference is rendered in
//! process with `tessera::render::render`, so the test also shows that passes equal one render.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};
use tessera::checkpoint::{
    load_checkpoint, read_checkpoint, write_checkpoint, CheckpointMeta, Continuation,
};
use tessera::image_io::{write_image, RgbImage};
use tessera::render::{render, render_span, Framebuffer, RenderOptions, Span};
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;
use tessera_scene::{load_scene, LoadedScene};

use crate::support;
use support::stderr;
use support::temp_dir::TempDir;

const BIN: &str = env!("CARGO_BIN_EXE_tessera");
const RES: &str = "12";
/// Large enough that the interrupted runs cannot finish before the signal (several seconds of
/// work; each interrupted run does a fraction of a second).
const LONG_SPP: u64 = 16384;

fn cbox() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml")
}

fn load() -> LoadedScene {
    let d = [("res".to_string(), RES.to_string())];
    load_scene(&cbox(), &d).unwrap()
}

/// A fresh temporary directory (`tessera-progressive-...`), removed on drop.
fn temp_dir(name: &str) -> TempDir {
    TempDir::new("tessera-progressive", name)
}

/// `tessera render cbox -D res=12 --tile-size 4 --threads 2 -q` plus `extra`.
fn cmd(extra: &[&str]) -> Command {
    let mut c = Command::new(BIN);
    c.arg("render")
        .arg(cbox())
        .args([
            "-D",
            &format!("res={RES}"),
            "--tile-size",
            "4",
            "--threads",
            "2",
            "-q",
        ])
        .args(extra)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    c
}

/// `tessera render cbox ARGS OUT` (ARGS ending with `-o`), run to its end.
fn render_cbox_to(args: &[&str], out: &Path) -> Output {
    Command::new(BIN)
        .arg("render")
        .arg(cbox())
        .args(args)
        .arg(out)
        .output()
        .unwrap()
}

fn run(extra: &[&str]) -> Output {
    cmd(extra).output().unwrap()
}

/// Waits until `path` exists (the run wrote its first checkpoint), or panics after 5 minutes.
fn wait_for_file(child: &mut Child, path: &Path) {
    let t = Instant::now();
    while !path.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!(
                "the render ended ({status}) before writing {}",
                path.display()
            );
        }
        assert!(
            t.elapsed() < Duration::from_secs(300),
            "no checkpoint after 5 minutes"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn signal(child: &Child, sig: &str) {
    let ok = Command::new("kill")
        .args([sig, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(ok.success(), "kill {sig} failed");
}

/// Starts a long render writing `ckpt` often, waits for the checkpoint, sends `sig`, and returns
/// the exit code (`None` if killed by the signal).
fn interrupted(extra: &[&str], ckpt: &Path, sig: &str) -> Option<i32> {
    let spp = LONG_SPP.to_string();
    let mut args = vec!["--spp", &spp, "--write-every", "0.1"];
    args.extend_from_slice(extra);
    let mut child = cmd(&args).spawn().unwrap();
    wait_for_file(&mut child, ckpt);
    signal(&child, sig);
    let out = child.wait_with_output().unwrap();
    assert!(
        !out.status.success(),
        "the render finished before the signal: raise LONG_SPP"
    );
    out.status.code()
}

fn reference(spp: u64) -> Framebuffer {
    let l = load();
    let opts = RenderOptions {
        threads: 2,
        tile_size: 4,
        ..Default::default()
    };
    let job = RenderJob::new(&l.scene, &l.integrator, l.seed);
    render(&job, 0..spp, &opts, &mut |_, _| {})
}

fn pfm_bytes(fb: &Framebuffer, dir: &TempDir) -> Vec<u8> {
    let p = dir.path("reference.pfm");
    let img = RgbImage {
        width: fb.width,
        height: fb.height,
        data: fb.rgb(),
    };
    write_image(&p, &img).unwrap();
    std::fs::read(p).unwrap()
}

fn one_line_exit_2(o: &Output, needles: &[&str]) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {e}");
    assert_eq!(e.trim_end().lines().count(), 1, "not one line: {e}");
    for needle in needles {
        assert!(e.contains(needle), "expected \"{needle}\" in: {e}");
    }
}

/// SIGINT, SIGTERM, SIGKILL, resume after each: the final image and sums equal one
/// uninterrupted render; a resume to another total spp gives other bits (control).
#[test]
fn interrupted_and_resumed_render_is_bit_identical() {
    let dir = temp_dir("resume");
    let ck = dir.path("render.ckpt");
    let out = dir.path("out.pfm");
    let ck_s = ck.to_str().unwrap();
    let out_s = out.to_str().unwrap();
    let spp = LONG_SPP.to_string();

    // 1. Ctrl-C: exit 130, image and checkpoint written.
    let code = interrupted(&["-o", out_s, "--checkpoint", ck_s], &ck, "-INT");
    assert_eq!(code, Some(130));
    assert!(out.exists());
    let first = load_checkpoint(&ck).unwrap();
    let counts: Vec<u64> = first.pixels.iter().map(|p| p.count + p.dropped).collect();
    let (lo, hi) = (counts.iter().min().unwrap(), counts.iter().max().unwrap());
    assert!(*hi < LONG_SPP && *hi > 0, "counts {lo}..{hi}");

    // 2. Resume, SIGTERM: exit 143, further along. (Each run resumes from a copy and writes
    //    `ck` afresh, so the test can wait for its first checkpoint.)
    let first_s = dir.path("first.ckpt");
    std::fs::rename(&ck, &first_s).unwrap();
    let code = interrupted(
        &[
            "-o",
            out_s,
            "--resume",
            first_s.to_str().unwrap(),
            "--checkpoint",
            ck_s,
        ],
        &ck,
        "-TERM",
    );
    assert_eq!(code, Some(143));
    let second = load_checkpoint(&ck).unwrap();
    let lo2 = second
        .pixels
        .iter()
        .map(|p| p.count + p.dropped)
        .min()
        .unwrap();
    assert!(lo2 >= *lo, "resumed run went backwards: {lo2} < {lo}");

    // 3. Resume, SIGKILL after a checkpoint: nothing written on the way out, the last
    //    checkpoint (atomically replaced) is intact.
    let keep = dir.path("before-kill.ckpt");
    std::fs::rename(&ck, &keep).unwrap();
    let keep_s = keep.to_str().unwrap();
    let code = interrupted(
        &["-o", out_s, "--resume", keep_s, "--checkpoint", ck_s],
        &ck,
        "-KILL",
    );
    assert_eq!(code, None, "SIGKILL has no exit code");
    load_checkpoint(&ck).expect("checkpoint readable after kill -9");

    // 4. Resume to the end.
    let o = run(&["-o", out_s, "--resume", ck_s, "--spp", &spp]);
    assert!(o.status.success(), "{}", stderr(&o));
    let done = load_checkpoint(&ck).unwrap();
    let want = reference(LONG_SPP);
    assert!(
        done.pixels == want.pixels,
        "resumed sums differ from one render"
    );
    let want_pfm = pfm_bytes(&want, &dir);
    assert_eq!(
        std::fs::read(&out).unwrap(),
        want_pfm,
        "resumed image differs"
    );

    // Control: continuing to another total spp gives other bits.
    let more = (LONG_SPP + 16).to_string();
    let o = run(&["-o", out_s, "--resume", ck_s, "--spp", &more]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_ne!(
        std::fs::read(&out).unwrap(),
        want_pfm,
        "control: more spp, same bits"
    );
    // And a target below what the checkpoint holds is refused.
    let o = run(&["-o", out_s, "--resume", ck_s, "--spp", "8"]);
    one_line_exit_2(&o, &["more than the target"]);
}

/// Pixels at different counts (as a stop at a tile boundary leaves them), saved to a checkpoint,
/// read back and continued, equal one render: each pixel continues from its own count. A stop
/// flag set before the pass renders nothing.
#[test]
fn mixed_counts_continue_to_one_render() {
    let l = load();
    let (w, h) = (l.scene.camera.width, l.scene.camera.height);
    let opts = RenderOptions {
        threads: 2,
        tile_size: 4,
        ..Default::default()
    };
    let job = RenderJob::new(&l.scene, &l.integrator, l.seed);
    let mut fb = reference(8);
    // Tiles of 4x4: some pixels back to 3 samples, some to none, the rest keep 8.
    for (i, p) in fb.pixels.iter_mut().enumerate() {
        let (x, y) = ((i % w as usize) as u32, (i / w as usize) as u32);
        if x < 4 {
            *p = Default::default();
            if y >= 4 {
                RenderJob::new(&l.scene, &l.integrator, l.seed).accumulate(x, y, 0..3, p);
            }
        }
    }
    let stop = AtomicBool::new(true);
    let before = fb.clone();
    let span = Span::UpTo(24);
    let complete =
        render_span::<NoProbe>(&job, &opts, &mut fb, span, Some(&stop), &mut |_, _| {}).complete;
    assert!(!complete, "a set stop flag did not stop the pass");
    assert!(fb == before, "a stopped pass changed pixels");
    let dir = temp_dir("mixed");
    let meta = CheckpointMeta {
        width: w,
        height: h,
        seed: l.seed,
        target_spp: 24,
        scene_hash: 1,
        passes: 0,
        seconds: 0.0,
        integrator: format!("{:?}", l.integrator),
        sampler_spp: 24,
    };
    let more = Continuation {
        splats: fb.splats.as_ref(),
        ..Continuation::default()
    };
    write_checkpoint(&dir.path("c"), &meta, &fb.pixels, more).unwrap();
    let back = read_checkpoint(&std::fs::read(dir.path("c")).unwrap()).unwrap();
    assert_eq!(back.meta, meta);
    let mut fb2 = Framebuffer::for_job(&job);
    fb2.pixels = back.pixels;
    if let Some(s) = &mut fb2.splats {
        s.sums = back.splats.expect("the checkpoint keeps the splatted sums");
    }
    stop.store(false, Ordering::SeqCst);
    let span = Span::UpTo(24);
    let complete =
        render_span::<NoProbe>(&job, &opts, &mut fb2, span, Some(&stop), &mut |_, _| {}).complete;
    assert!(complete);
    assert!(
        fb2.pixels == reference(24).pixels,
        "continued render differs"
    );
    // Control: one spp fewer is other bits.
    assert!(fb2.pixels != reference(23).pixels);
}

/// A valid small checkpoint to refuse in the tests below.
fn small_checkpoint(dir: &TempDir) -> PathBuf {
    let ck = dir.path("small.ckpt");
    let o = run(&[
        "--spp",
        "2",
        "-o",
        dir.path("small.pfm").to_str().unwrap(),
        "--checkpoint",
        ck.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    ck
}

#[test]
fn resume_of_another_render_is_refused() {
    let dir = temp_dir("mismatch");
    let ck = small_checkpoint(&dir);
    let ck_s = ck.to_str().unwrap();
    let out = dir.path("o.pfm");
    let out_s = out.to_str().unwrap();
    // Same everything: fine (the control).
    let o = run(&["-o", out_s, "--resume", ck_s, "--spp", "4"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let cases: &[(&[&str], &str)] = &[
        (&["--seed", "5"], "seed"),
        (&["-D", "rr_depth=4"], "another scene"),
        (&["--resolution-scale", "2"], "12x12, this render 24x24"),
        (&["--max-depth", "3"], "integrator"),
        (&["--integrator", "direct"], "integrator"),
    ];
    for (extra, needle) in cases {
        let mut a = vec!["-o", out_s, "--resume", ck_s, "--spp", "8"];
        a.extend_from_slice(extra);
        one_line_exit_2(&run(&a), &[needle, ck_s]);
    }
    // Another scene file with the same settings.
    let other = dir.path("other.xml");
    let text = std::fs::read_to_string(cbox())
        .unwrap()
        .replace("Cornell box", "Cornell box!");
    std::fs::write(&other, text).unwrap();
    // Relative mesh paths resolve beside the scene file.
    let meshes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/meshes");
    std::os::unix::fs::symlink(meshes, dir.path("meshes")).unwrap();
    let o = Command::new(BIN)
        .arg("render")
        .arg(&other)
        .args(["-D", "res=12", "-q", "-o", out_s, "--resume", ck_s])
        .output()
        .unwrap();
    one_line_exit_2(&o, &["another scene"]);
}

#[test]
fn damaged_checkpoints_are_refused() {
    let dir = temp_dir("damaged");
    let ck = small_checkpoint(&dir);
    let bytes = std::fs::read(&ck).unwrap();
    let out = dir.path("o.pfm");
    let bad = dir.path("bad.ckpt");
    let bad_s = bad.to_str().unwrap();
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 2] ^= 0x10;
    let mut huge = bytes.clone();
    huge[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (bytes[..bytes.len() / 2].to_vec(), "truncated"),
        (bytes[..bytes.len() - 1].to_vec(), "truncated"),
        (flipped, "checksum"),
        (huge, "truncated"),
        (Vec::new(), "truncated"),
        (
            b"not a checkpoint at all, just some text padding it out to 80 bytes or so....."
                .to_vec(),
            "magic",
        ),
    ];
    for (content, needle) in cases {
        std::fs::write(&bad, &content).unwrap();
        let o = run(&["-o", out.to_str().unwrap(), "--resume", bad_s]);
        one_line_exit_2(&o, &[needle, bad_s]);
        assert!(!out.exists(), "an output was written from a bad checkpoint");
    }
    let o = run(&[
        "-o",
        out.to_str().unwrap(),
        "--resume",
        dir.path("missing").to_str().unwrap(),
    ]);
    one_line_exit_2(&o, &["cannot read checkpoint"]);
}

#[test]
fn time_budget_stops_the_render() {
    let dir = temp_dir("time");
    let out = dir.path("t.exr");
    let t = Instant::now();
    let o = render_cbox_to(
        &["-D", "res=12", "--threads", "2", "--time", "0.5", "-o"],
        &out,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("time budget spent"), "{}", stderr(&o));
    assert!(out.exists());
    // Generous: only that it did stop, not how precisely.
    assert!(t.elapsed() < Duration::from_secs(120));
    // With a small --spp as well, the target comes first.
    let o = render_cbox_to(
        &["-D", "res=12", "--time", "1000", "--spp", "3", "-o"],
        &out,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("at 3 spp"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("time budget"));
}

/// `--resolution-scale 0.5` of a 24-pixel film is the 12-pixel film: the same bits.
#[test]
fn resolution_scale_gives_the_smaller_film() {
    let dir = temp_dir("scale");
    let (a, b, c) = (dir.path("a.pfm"), dir.path("b.pfm"), dir.path("c.pfm"));
    let o = run(&["--spp", "2", "-o", a.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = render_cbox_to(
        &[
            "-D",
            "res=24",
            "--spp",
            "2",
            "-q",
            "--resolution-scale",
            "0.5",
            "-o",
        ],
        &b,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    // Control: the unscaled 24-pixel film is another image; a zero scale is refused.
    let o = render_cbox_to(&["-D", "res=24", "--spp", "2", "-q", "-o"], &c);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_ne!(std::fs::read(&a).unwrap(), std::fs::read(&c).unwrap());
    one_line_exit_2(
        &run(&["--resolution-scale", "0", "-o", c.to_str().unwrap()]),
        &["--resolution-scale"],
    );
    // A scale that would drop below one pixel keeps one.
    let o = run(&[
        "--spp",
        "1",
        "--resolution-scale",
        "0.001",
        "-o",
        c.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read(&c).unwrap().starts_with(b"PF\n1 1\n"));
}

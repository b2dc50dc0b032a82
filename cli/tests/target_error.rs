//! `render --target-error` (`progressive::Plan::target_error`, `tessera_core::error_estimate`):
//! the estimate follows the real error against Mitsuba's converged references (where the sample
//! variance overstates it under zsobol), the render stops at the first check point that reaches
//! the target with the same bits for any thread count and tile size, and bad values or flags it
//! cannot honour get one line and exit code 2.

use std::path::{Path, PathBuf};
use tessera::checkpoint::{
    read_checkpoint, write_checkpoint, Checkpoint, CheckpointMeta, Continuation,
};
use tessera::image_io::read_image;
use tessera::progressive::check::CheckState;
use tessera::progressive::{self, Ending, Outcome, Plan};
use tessera::render::Framebuffer;
use tessera_core::adaptive::{relative_variance, AdaptiveParams};
use tessera_lab::bench::errors;
use tessera_scene::{load_scene, LoadedScene};

use crate::support;
use support::{run, stderr};

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../scenes/{name}.xml"))
}

/// `name` at `res` x `res`, box filter, `sampler` set up for 64 samples per pixel.
fn load(name: &str, res: u32, sampler: &str) -> LoadedScene {
    let defines: Vec<(String, String)> = [("res", res.to_string()), ("rfilter", "box".into())]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
    let mut l = load_scene(&scene_path(name), &defines).expect("scene loads");
    l.set_sampler(Some(sampler), 64).unwrap();
    l
}

/// A progressive render with a target error, up to `spp`.
fn render(
    l: &LoadedScene,
    spp: u64,
    target_error: f64,
    threads: usize,
    tile_size: u32,
    seed: u64,
    adaptive: bool,
) -> (Framebuffer, Outcome) {
    let (w, h) = (l.scene.camera.width, l.scene.camera.height);
    let mut fb = Framebuffer::new(w, h);
    let plan = Plan {
        target: Some(spp),
        target_error: Some(target_error),
        adaptive: adaptive.then(AdaptiveParams::default),
        ..Default::default()
    };
    let out = support::run_plan(support::job(l, seed, threads, tile_size), &mut fb, &plan);
    (fb, out)
}

const SEEDS: u64 = 6;

/// The estimate against the real relMSE (the scene's 64x64 Mitsuba reference) at 64 spp,
/// averaged over [`SEEDS`] seeds: (real / halves estimate, real / sample-variance estimate).
fn calibration(name: &str, sampler: &str) -> (f64, f64) {
    let l = load(name, 64, sampler);
    let reference = read_image(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join(format!("../scenes/refs/{name}_64x64_mitsuba.exr")),
    )
    .unwrap();
    let (mut halves, mut variance) = (0.0, 0.0);
    for seed in 0..SEEDS {
        // A target nothing reaches: the render runs to 64 spp, estimating at 16, 32 and 64.
        let (fb, out) = render(&l, 64, 1e-12, 2, 16, seed, false);
        assert_eq!(out.ending, Ending::Target);
        let real = errors(&fb.rgb(), &reference.data).relmse;
        let from_variance = fb
            .pixels
            .iter()
            .map(|p| relative_variance(p, 0.01).unwrap() / p.count as f64)
            .sum::<f64>()
            / fb.pixels.len() as f64;
        halves += real / out.estimate.unwrap() / SEEDS as f64;
        variance += real / from_variance / SEEDS as f64;
    }
    (halves, variance)
}

/// The estimate is what the feature stands on: it must be within a factor of 1.6 of the real
/// error either way. Measured (64x64, 64 spp, seeds 0-5), real / estimate with the halves, then
/// with the sample variance: cbox independent 1.18 and 1.18, zsobol 0.69 and 0.47; veach_mis
/// independent 1.43 and 1.35 (rare bright paths not yet seen at 64 spp), zsobol 1.07 and 0.40.
/// The control: under zsobol the sample variance overstates the error by more than 1.6 on both
/// scenes, so the band can fail.
#[test]
fn estimate_follows_the_real_error() {
    for name in ["cbox", "veach_mis"] {
        for sampler in ["independent", "zsobol"] {
            let (halves, variance) = calibration(name, sampler);
            assert!(
                (1.0 / 1.6..1.6).contains(&halves),
                "{name} {sampler}: real / estimate {halves:.2}"
            );
            if sampler == "zsobol" {
                assert!(
                    !(1.0 / 1.6..1.6).contains(&variance),
                    "control, {name}: real / sample-variance estimate {variance:.2}"
                );
            }
        }
    }
}

fn spp_of(fb: &Framebuffer) -> (u64, u64) {
    progressive::spp_range(fb)
}

/// The render stops at the first power of two whose estimate is at most the target: the
/// previous one's was above it (found by rendering to half the count with a target nothing
/// reaches), with the same bits for 1 and 2 threads and any tile size. Adaptive renders stop at
/// a doubling of the mean the same way.
#[test]
fn stops_at_the_first_check_point_below_the_target() {
    for adaptive in [false, true] {
        let l = load("cbox", 32, "zsobol");
        let target = 4e-3;
        let (fb, out) = render(&l, 4096, target, 2, 16, 5, adaptive);
        assert_eq!(out.ending, Ending::ErrorReached, "adaptive {adaptive}");
        let e = out.estimate.unwrap();
        assert!(e <= target, "{e}");
        let n = fb.pixels.iter().map(|p| p.count + p.dropped).sum::<u64>() / fb.pixels.len() as u64;
        assert!(n.is_power_of_two() && n >= 32, "{n}");
        if !adaptive {
            assert_eq!(spp_of(&fb), (n, n));
        }
        let (_, before) = render(&l, n / 2, 1e-12, 2, 16, 5, adaptive);
        assert_eq!(before.ending, Ending::Target);
        assert!(before.estimate.unwrap() > target, "{before:?}");
        for (threads, tile) in [(1, 32), (2, 5), (3, 7)] {
            let (other, o) = render(&l, 4096, target, threads, tile, 5, adaptive);
            assert_eq!(o, out, "{threads} threads, tile {tile}");
            assert_eq!(other.rgb(), fb.rgb(), "{threads} threads, tile {tile}");
        }
    }
}

/// A render stopped at any pass and resumed from its checkpoint file (the interrupted adaptive
/// pass's targets and the last check point in it) stops at the same check point with the same
/// bits and estimate as one that never stopped; a finished one resumed has nothing left to do.
/// Control: resumed without the check point after the state that the stopping check compares
/// with, that check lacks its first half, so the render stops later.
#[test]
fn interrupted_and_resumed_stops_at_the_same_check_point() {
    let l = load("cbox", 32, "zsobol");
    let (w, h) = (l.scene.camera.width, l.scene.camera.height);
    let target = 4e-3;
    let path = std::env::temp_dir().join(format!("tessera-te-{}.ckpt", std::process::id()));
    let meta = CheckpointMeta {
        width: w,
        height: h,
        seed: 5,
        target_spp: 4096,
        scene_hash: 1,
        passes: 0,
        seconds: 0.0,
        integrator: "test".into(),
        sampler_spp: 0,
    };
    for adaptive in [false, true] {
        let (want, want_out) = render(&l, 4096, target, 2, 16, 5, adaptive);
        assert_eq!(want_out.ending, Ending::ErrorReached);
        // Tiles of 4 (64 of them), so that the workers see a stop requested at a pass's first
        // tile before they finish the pass, even on a loaded machine (tiles change no bit).
        let job = support::job(&l, 5, 2, 4);
        let plan = Plan {
            target: Some(4096),
            target_error: Some(target),
            adaptive: adaptive.then(AdaptiveParams::default),
            ..Default::default()
        };
        let resume = |ck: &Checkpoint, check: Option<CheckState>| {
            let mut fb = Framebuffer::new(w, h);
            fb.pixels = ck.pixels.clone();
            let plan = Plan {
                pending: ck.pending.clone(),
                resumed_check: check,
                ..plan.clone()
            };
            let out = support::run_plan(job, &mut fb, &plan);
            (fb, out)
        };
        let mut later = 0;
        // Where the render stops (mean spp).
        let last = progressive::taken(&want) / want.pixels.len() as u64;
        for stop_after in 0..12u64 {
            let mut fb = Framebuffer::new(w, h);
            let out = support::run_stopped_in_pass(job, &mut fb, &plan, stop_after);
            let more = Continuation {
                pending: out.pending.as_deref(),
                check: out.check.as_ref(),
                splats: None,
            };
            write_checkpoint(&path, &meta, &fb.pixels, more).unwrap();
            let ck = read_checkpoint(&std::fs::read(&path).unwrap()).unwrap();
            let (again, o) = resume(&ck, ck.check.clone());
            let what = format!(
                "adaptive {adaptive}, stop after {stop_after}: {:?}",
                out.ending
            );
            assert!(again.pixels == want.pixels, "{what}");
            assert_eq!(
                (o.ending, o.estimate),
                (Ending::ErrorReached, want_out.estimate),
                "{what}"
            );
            if out.ending == Ending::ErrorReached {
                assert_eq!(o.passes, 0, "{what}: finished, nothing left to do");
            } else if ck.check.as_ref().is_some_and(|c| 2 * c.spp >= last) {
                // Past the state the stopping check compares with: without it, no stop there.
                let (blind, _) = resume(&ck, None);
                assert!(blind.pixels != want.pixels, "control, {what}");
                later += 1;
            }
        }
        // One stop position at least (the last pass) is past the stopping check's first half.
        assert!(later >= 1, "adaptive {adaptive}: no stop past the half");
    }
    let _ = std::fs::remove_file(&path);
}

#[test]
fn command_line() {
    let dir = std::env::temp_dir().join(format!("tessera-target-error-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out.exr");
    let out = out.to_str().unwrap();
    let scene = scene_path("cbox");
    let scene = scene.to_str().unwrap();
    let base = ["render", scene, "-D", "res=16", "-D", "rfilter=box"];
    let with = |extra: &[&str]| {
        let mut a = base.to_vec();
        a.extend_from_slice(extra);
        a.extend_from_slice(&["-o", out]);
        let _ = std::fs::remove_file(out);
        run(&a)
    };
    // Without --spp there is no sample limit: the estimate ends the render and is reported.
    let o = with(&["--target-error", "0.02"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("estimated relMSE") && e.contains("target 2.00e-2"),
        "{e}"
    );
    assert!(Path::new(out).exists());
    // A target not reached within --spp: the sample limit ends it.
    let o = with(&["--target-error", "1e-9", "--spp", "32"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(e.contains("at 32 spp"), "{e}");
    // Through a checkpoint file: a finished render resumed with its target has nothing left to
    // do; resumed with a lower target it ends where a fresh render with that target does.
    let ck = dir.join("c.ckpt");
    let ck = ck.to_str().unwrap();
    let pfm = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let render_to = |out: &str, extra: &[&str]| {
        let mut a = base.to_vec();
        a.extend_from_slice(extra);
        a.extend_from_slice(&["-o", out]);
        let o = run(&a);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        (stderr(&o), std::fs::read(out).unwrap())
    };
    let (_, first) = render_to(
        &pfm("a.pfm"),
        &["--target-error", "0.02", "--checkpoint", ck],
    );
    let (e, again) = render_to(&pfm("b.pfm"), &["--target-error", "0.02", "--resume", ck]);
    assert!(e.contains(" 0 passes"), "{e}");
    assert!(again == first);
    let (_, lower) = render_to(&pfm("c.pfm"), &["--target-error", "0.005", "--resume", ck]);
    let (_, fresh) = render_to(&pfm("d.pfm"), &["--target-error", "0.005"]);
    assert!(lower == fresh && lower != first);
    for bad in [
        &["--target-error", "0"][..],
        &["--target-error", "-1"],
        &["--target-error", "NaN"],
        &["--target-error", "inf"],
        &["--target-error", "1e-3", "--stats"],
        &["--target-error", "1e-3", "--tiles", "1/2"],
        &["--target-error", "1e-3", "--forever"],
    ] {
        let o = with(bad);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {e}");
        assert!(e.contains("--target-error"), "{bad:?}: {e}");
        assert_eq!(e.trim_end().lines().count(), 1, "{bad:?}: {e}");
        assert!(!Path::new(out).exists(), "{bad:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

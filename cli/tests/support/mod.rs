//! Helpers shared by the driver's integration tests (a directory, so Cargo does not build it as a
//! test of its own). Each test file uses a part of them, so the rest is not dead code there.
#![allow(dead_code)]
use std::process::{Command, Output};
use std::sync::atomic::{AtomicBool, Ordering};
use tessera::progressive::{self, Outcome, Plan};
use tessera::render::{render, Framebuffer, RenderOptions};
use tessera_core::adaptive::AdaptiveParams;
use tessera_core::render::RenderJob;
use tessera_scene::LoadedScene;

pub mod temp_dir;

/// A render job with its threads and tile edge.
#[derive(Clone, Copy)]
pub struct Job<'a> {
    /// What is rendered.
    pub render: RenderJob<'a>,
    /// Worker threads.
    pub threads: usize,
    /// Tile edge in pixels.
    pub tile_size: u32,
}

/// The job of rendering `l` with `seed` on `threads` threads in tiles of `tile_size` pixels.
pub fn job(l: &LoadedScene, seed: u64, threads: usize, tile_size: u32) -> Job<'_> {
    Job {
        render: RenderJob::new(&l.scene, &l.integrator, seed),
        threads,
        tile_size,
    }
}

/// Runs `plan` into `fb` (which may hold a resumed render) to its end, writing nothing.
pub fn run_plan(job: Job, fb: &mut Framebuffer, plan: &Plan) -> Outcome {
    run_passes(job, fb, plan, None)
}

/// Runs `plan` into `fb` and requests a stop as soon as pass `pass` (counted from 0) is under way,
/// as a signal would; nothing is written on the way.
pub fn run_stopped_in_pass(job: Job, fb: &mut Framebuffer, plan: &Plan, pass: u64) -> Outcome {
    run_passes(job, fb, plan, Some(pass))
}

fn run_passes(job: Job, fb: &mut Framebuffer, plan: &Plan, stop_in: Option<u64>) -> Outcome {
    let stop = AtomicBool::new(false);
    let opts = RenderOptions {
        threads: job.threads,
        tile_size: job.tile_size,
        ..Default::default()
    };
    progressive::run(
        &job.render,
        &opts,
        fb,
        plan,
        &stop,
        &mut |s| {
            if stop_in == Some(s.passes) {
                stop.store(true, Ordering::SeqCst);
            }
        },
        &mut |_, _, _| Ok(()),
    )
    .expect("renders")
}

/// Runs the `tessera` binary with `args` given as OS strings (paths among them).
pub fn run_os(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tessera"))
        .args(args)
        .output()
        .expect("cannot run the tessera binary")
}

/// Runs the `tessera` binary with `args`.
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tessera"))
        .args(args)
        .output()
        .expect("cannot run tessera")
}

/// A command's standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Samples `0..spp` of `l` with `seed`, rendered at once (no passes) on 2 threads in 16-pixel
/// tiles.
pub fn render_plain(l: &LoadedScene, spp: u64, seed: u64) -> Framebuffer {
    let opts = RenderOptions {
        threads: 2,
        tile_size: 16,
        pixels: Default::default(),
    };
    let job = RenderJob::new(&l.scene, &l.integrator, seed);
    render(&job, 0..spp, &opts, &mut |_, _| {})
}

/// `fb` with every pixel's ray count cleared: an adaptive render's sums, to compare with a
/// plain render's (which counts no rays).
pub fn uncounted(mut fb: Framebuffer) -> Framebuffer {
    for p in &mut fb.pixels {
        p.rays = 0;
    }
    fb
}

/// An adaptive render of `l` to a mean of `spp` samples per pixel, from a blank framebuffer,
/// with how it ended.
pub fn render_adaptive(job: Job, spp: u64, params: AdaptiveParams) -> (Framebuffer, Outcome) {
    let camera = &job.render.scene.camera;
    let mut fb =
        Framebuffer::with_footprint(camera.width, camera.height, job.render.scene.splat.as_ref());
    let plan = Plan {
        target: Some(spp),
        adaptive: Some(params),
        ..Default::default()
    };
    let out = run_plan(job, &mut fb, &plan);
    (fb, out)
}

/// Each pixel's sample count (`count + dropped`).
pub fn sample_counts(fb: &Framebuffer) -> Vec<u64> {
    fb.pixels.iter().map(|p| p.count + p.dropped).collect()
}

/// How many pixels of `a` and `b` differ in any bit of their accumulators.
pub fn differing_pixels(a: &Framebuffer, b: &Framebuffer) -> usize {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| p.to_words() != q.to_words())
        .count()
}

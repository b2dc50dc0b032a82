//! Helpers shared by the driver's integration tests (a directory, so Cargo does not build it as a
//! test of its own).
use std::process::{Command, Output};
use std::sync::atomic::{AtomicBool, Ordering};
use tessera::progressive::{self, Outcome, Plan};
use tessera::render::{Framebuffer, RenderOptions};
use tessera_core::render::RenderJob;
use tessera_scene::LoadedScene;

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

//! `tessera render`: load, render progressively on worker threads, write every requested output.
//!
//! Stopping rule: `--spp N` (default: the scene's `sample_count`), `--time SECONDS` (a time
//! budget; with `--spp` too, whichever comes first), `--target-error E` (the first power of two
//! spp whose estimated relative MSE is at most `E`; with `--spp` or `--time`, whichever comes
//! first), `--forever` (until Ctrl-C / SIGTERM).
//! SIGINT / SIGTERM stop at the next tile boundary, write the outputs (and the checkpoint, with
//! `--checkpoint`) and exit 130 / 143; a second signal exits at once without writing.
//! `--resume FILE` continues a checkpoint to the same bits as an uninterrupted render.
use super::decor::{spp_text, Decor};
pub use super::render_args::RenderArgs;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tessera::checkpoint::{load_checkpoint, write_checkpoint, CheckpointMeta, Continuation};
use tessera::image_io::Format;
use tessera::progressive::bar::{progress_bar, update_bar};
use tessera::progressive::{self, spp_range, Ending, Plan, Status};
use tessera::render::Framebuffer;
use tessera::render::RenderOptions;
use tessera_core::adaptive::{AdaptiveParams, ZSOBOL_BLOCK_FACTOR};
use tessera_core::camera::Camera;
use tessera_core::render::RenderJob;
use tessera_scene::error::InputError;
use tessera_scene::{load_scene_as, MAX_EDGE, MAX_PIXELS};

fn usage(msg: String) -> i32 {
    eprintln!("error: {msg}");
    InputError::EXIT_CODE
}

fn seconds(name: &str, v: Option<f64>) -> Result<Option<Duration>, String> {
    match v {
        None => Ok(None),
        Some(s) if s.is_finite() && s > 0.0 && s < 1e9 => Ok(Some(Duration::from_secs_f64(s))),
        Some(s) => Err(format!(
            "--{name} must be a positive number of seconds, found {s}"
        )),
    }
}

/// Ctrl-C / SIGTERM: the first sets `stop` (and `code` to 130 / 143), a second exits at once.
fn register_signals(stop: &Arc<AtomicBool>, code: &Arc<AtomicUsize>) -> Result<(), String> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use signal_hook::flag;
    let signalled = Arc::new(AtomicBool::new(false));
    for (sig, exit) in [(SIGINT, 130), (SIGTERM, 143)] {
        // The shutdown goes first: it fires only if an earlier signal already armed it.
        flag::register_conditional_shutdown(sig, exit, Arc::clone(&signalled))
            .and_then(|_| flag::register_usize(sig, Arc::clone(code), exit as usize))
            .and_then(|_| flag::register(sig, Arc::clone(stop)))
            .and_then(|_| flag::register(sig, Arc::clone(&signalled)))
            .map_err(|e| format!("cannot install signal handlers: {e}"))?;
    }
    Ok(())
}

/// Runs the command; returns the exit code.
pub fn run(args: &RenderArgs) -> i32 {
    for o in &args.outputs {
        if Format::from_path(o).is_none() {
            return usage(format!(
                "{}: unknown output format (use .exr, .pfm or .png)",
                o.display()
            ));
        }
    }
    if args.tile_size == 0 || args.tile_size > 4096 {
        return usage(format!(
            "--tile-size must be between 1 and 4096, found {}",
            args.tile_size
        ));
    }
    if args.spp == Some(0) {
        return usage("--spp must be at least 1".into());
    }
    if let Some(e) = args.target_error.filter(|e| !(e.is_finite() && *e > 0.0)) {
        return usage(format!(
            "--target-error must be a positive relative MSE, found {e}"
        ));
    }
    let (budget, write_every) = match (
        seconds("time", args.time),
        seconds("write-every", args.write_every),
    ) {
        (Ok(b), Ok(w)) => (b, w),
        (Err(e), _) | (_, Err(e)) => return usage(e),
    };
    let mut loaded = match load_scene_as(&args.scene, &args.defines, args.dialect) {
        Ok(l) => l,
        Err(e) => return usage(e.to_string()),
    };
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    if let Err(e) = loaded.set_integrator(args.integrator.as_deref(), args.max_depth) {
        return usage(e);
    }
    let resumed = match args.resume.as_deref().map(load_checkpoint).transpose() {
        Ok(c) => c,
        Err(e) => return usage(e),
    };
    // zsobol's pixel blocks follow the count the render was started for: --spp, else the
    // scene's sample count (never --time), so that progressive passes draw one sequence; a
    // resumed render keeps the count its first run recorded, whatever --spp it asks for now.
    // Adaptive renders give noisy pixels several times the mean: their blocks are
    // ZSOBOL_BLOCK_FACTOR times larger, so those pixels stay in one block.
    let sampler_spp = match &resumed {
        Some(ck) => ck.meta.sampler_spp,
        None => args.spp.unwrap_or(0),
    };
    let factor = if args.adaptive {
        ZSOBOL_BLOCK_FACTOR
    } else {
        1
    };
    let set = match sampler_spp {
        0 => loaded.set_sampler(args.sampler.as_deref(), loaded.spp.saturating_mul(factor)),
        n => loaded.set_sampler_for(args.sampler.as_deref(), n.saturating_mul(factor)),
    };
    if let Err(e) = set {
        return usage(e);
    }
    if args.filter_sampling {
        loaded.scene.splat = None;
    }
    if let Some(f) = args.resolution_scale {
        if let Err(e) = scale_resolution(&mut loaded.scene.camera, f) {
            return usage(e);
        }
    }
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if threads == 0 {
        return usage("--threads must be at least 1".into());
    }
    let seed = args.seed.unwrap_or(loaded.seed);
    if let Err(e) = super::render_layers::check_args(args, &loaded) {
        return usage(e);
    }
    if super::render_once::wanted(args) {
        return super::render_once::run(args, &loaded, threads, seed);
    }
    let (w, h) = (loaded.scene.camera.width, loaded.scene.camera.height);
    let mut meta = CheckpointMeta {
        width: w,
        height: h,
        seed,
        target_spp: 0,
        scene_hash: loaded.source_hash,
        passes: 0,
        seconds: 0.0,
        sampler_spp,
        integrator: format!(
            "{:?}, sampler {:?}{}",
            loaded.integrator,
            loaded.scene.sampler,
            match args.adaptive {
                true => format!(", adaptive {:?}", AdaptiveParams::default()),
                false => String::new(),
            }
        ),
    };
    let mut fb = Framebuffer::with_footprint(w, h, loaded.scene.splat.as_ref());
    if super::render_layers::wants_squares(args, &loaded) {
        fb = fb.with_squares();
    }
    fb = fb.with_aovs(super::render_layers::gathered_aovs(args, &loaded));
    let mut resumed_target = None;
    let mut pending = None;
    let mut resumed_check = None;
    if let (Some(path), Some(ck)) = (&args.resume, resumed) {
        if let Err(e) = ck.meta.matches(&meta) {
            return usage(format!("{}: {e}", path.display()));
        }
        meta.passes = ck.meta.passes;
        meta.seconds = ck.meta.seconds;
        resumed_target = (ck.meta.target_spp > 0).then_some(ck.meta.target_spp);
        fb.pixels = ck.pixels;
        match (&mut fb.splats, ck.splats) {
            (None, None) => {}
            (Some(s), Some(sums)) if sums.len() == s.sums.len() => s.sums = sums,
            _ => {
                return usage(format!(
                    "{}: the checkpoint's reconstruction (splatted or not, and the filter's reach) is not this render's",
                    path.display()
                ))
            }
        }
        pending = ck.pending;
        // The check point matters only to a render that checks (it stays in the file otherwise
        // only until the next write).
        resumed_check = ck.check.filter(|_| args.target_error.is_some());
    }
    let target = if args.forever {
        None
    } else if let Some(n) = args.spp.or(resumed_target) {
        Some(n)
    } else if budget.is_some() || args.target_error.is_some() {
        None
    } else {
        Some(loaded.spp)
    };
    // Adaptive renders count the mean (single pixels may well be past the target).
    let (what, high) = match args.adaptive {
        true => (
            "a mean of",
            progressive::taken(&fb) / (fb.pixels.len() as u64).max(1),
        ),
        false => ("pixels at", spp_range(&fb).1),
    };
    if let Some(t) = target.filter(|t| *t < high) {
        let path = args.resume.as_deref().unwrap_or(args.scene.as_path());
        return usage(format!(
            "{}: the checkpoint already has {what} {high} spp, more than the target {t}",
            path.display()
        ));
    }
    meta.target_spp = target.unwrap_or(0);
    let checkpoint = args.checkpoint.clone().or_else(|| args.resume.clone());
    let stop = Arc::new(AtomicBool::new(false));
    let signal = Arc::new(AtomicUsize::new(0));
    if let Err(e) = register_signals(&stop, &signal) {
        eprintln!("error: {e}");
        return 1;
    }
    let (bar, mode) = progress_bar(args.quiet, target, budget, w as u64 * h as u64);
    let job = RenderJob::new(&loaded.scene, &loaded.integrator, meta.seed);
    let opts = RenderOptions {
        threads,
        tile_size: args.tile_size,
        ..Default::default()
    };
    let plan = Plan {
        target,
        budget,
        write_every,
        adaptive: args.adaptive.then(AdaptiveParams::default),
        target_error: args.target_error,
        pending,
        resumed_check,
    };
    let taken = progressive::taken;
    let samples_before = taken(&fb);
    let start = Instant::now();
    let base = meta.clone();
    let decor = Decor::new(args, &loaded);
    let save = |fb: &Framebuffer, passes: u64, more: Continuation| -> Result<(), String> {
        let mut m = base.clone();
        m.passes += passes;
        m.seconds += start.elapsed().as_secs_f64();
        write_all(&args.outputs, checkpoint.as_deref(), &m, fb, more, &decor)
    };
    let result = progressive::run(
        &job,
        &opts,
        &mut fb,
        &plan,
        &stop,
        &mut |s: &Status| update_bar(&bar, mode, s),
        &mut |fb, passes, check| {
            save(
                fb,
                passes,
                Continuation {
                    pending: None,
                    check,
                    splats: fb.splats.as_ref(),
                },
            )
        },
    );
    bar.finish_and_clear();
    let progressive::Outcome {
        ending,
        passes,
        estimate,
        pending,
        check,
    } = match result {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return 1;
        }
    };
    let more = Continuation {
        pending: pending.as_deref(),
        check: check.as_ref(),
        splats: fb.splats.as_ref(),
    };
    let written = match loaded.integrator_spec.layers.is_empty() {
        true => save(&fb, passes, more),
        false => {
            let secs = start.elapsed().as_secs_f64();
            super::render_layers::write(args, &loaded, &fb, seed, &opts, &decor, secs)
        }
    };
    if let Err(e) = written {
        eprintln!("error: {e}");
        return 1;
    }
    let secs = start.elapsed().as_secs_f64();
    let spp = spp_text(&fb);
    let code = signal.load(Ordering::SeqCst) as i32;
    if !args.quiet || code != 0 {
        let error = match (args.target_error, estimate) {
            (Some(t), Some(e)) => format!("; estimated relMSE {e:.2e} (target {t:.2e})"),
            (Some(t), None) => format!("; relMSE not yet estimated (target {t:.2e})"),
            _ => String::new(),
        };
        eprintln!(
            "{w}x{h} at {spp} spp, {passes} passes in {secs:.2} s ({:.2} M samples/s, {threads} threads); {} non-finite samples dropped{}{error}",
            (taken(&fb) - samples_before) as f64 / secs.max(1e-9) / 1e6,
            fb.dropped(),
            match ending {
                Ending::Target | Ending::ErrorReached => "",
                Ending::Time => "; time budget spent",
                Ending::Stopped => "; interrupted",
            }
        );
    }
    if code != 0 {
        match &checkpoint {
            Some(c) => eprintln!("checkpoint written: resume with --resume {}", c.display()),
            None => eprintln!("no --checkpoint given: this render cannot be resumed"),
        }
    }
    code
}

/// Writes the average to every output, then the checkpoint (each atomically), with what the
/// render needs to go on the same way (`more`).
fn write_all(
    outputs: &[PathBuf],
    checkpoint: Option<&std::path::Path>,
    meta: &CheckpointMeta,
    fb: &Framebuffer,
    more: Continuation,
    decor: &Decor,
) -> Result<(), String> {
    for o in outputs {
        decor.write(o, fb, meta.seconds)?;
    }
    if let Some(c) = checkpoint {
        write_checkpoint(c, meta, &fb.pixels, more)?;
    }
    Ok(())
}

/// `--resolution-scale`: multiplies the film's width and height (rounded, at least 1 pixel)
/// keeping the field of view (the camera maps the film to the same view whatever its size).
fn scale_resolution(camera: &mut Camera, f: f64) -> Result<(), String> {
    if !(f.is_finite() && f > 0.0 && f <= 16.0) {
        return Err(format!("--resolution-scale must be in (0, 16], found {f}"));
    }
    let scale = |n: u32| ((n as f64 * f).round() as i64).clamp(1, MAX_EDGE);
    let (w, h) = (scale(camera.width), scale(camera.height));
    if w * h > MAX_PIXELS {
        return Err(format!(
            "--resolution-scale {f} gives {w}x{h} pixels, over the limit of {MAX_PIXELS}"
        ));
    }
    (camera.width, camera.height) = (w as u32, h as u32);
    Ok(())
}

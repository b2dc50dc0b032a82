//! `tessera render` in one pass: split renders (`--crop`, `--tiles`, `--sample-range`, whose EXR
//! outputs are part files for `tessera merge`), `--stats` and `--debug-pixel`. These render a
//! fixed sample range once, so they do not combine with the progressive flags (`--time`,
//! `--forever`, `--write-every`, `--checkpoint`, `--resume`, `--adaptive`, `--target-error`).
use super::decor::Decor;
use super::render_args::RenderArgs;
use super::split_args::write_render_output;
use indicatif::{ProgressBar, ProgressStyle};
use std::time::Instant;
use tessera::render::RenderOptions;
use tessera::render_stats::render_maybe_stats;
use tessera_core::render::RenderJob;
use tessera_scene::error::InputError;
use tessera_scene::LoadedScene;

/// Whether the arguments ask for a one-pass render.
pub fn wanted(args: &RenderArgs) -> bool {
    args.split.is_split() || args.probe.stats || args.probe.debug_pixel.is_some()
}

/// The first progressive flag given, which a one-pass render cannot honour.
pub(crate) fn progressive_flag(args: &RenderArgs) -> Option<&'static str> {
    [
        (args.time.is_some(), "--time"),
        (args.forever, "--forever"),
        (args.write_every.is_some(), "--write-every"),
        (args.checkpoint.is_some(), "--checkpoint"),
        (args.resume.is_some(), "--resume"),
        (args.adaptive, "--adaptive"),
        (args.target_error.is_some(), "--target-error"),
    ]
    .into_iter()
    .find_map(|(given, name)| given.then_some(name))
}

/// Renders once and writes every output; returns the exit code.
pub fn run(args: &RenderArgs, loaded: &LoadedScene, threads: usize, seed: u64) -> i32 {
    let usage = |msg: String| {
        eprintln!("error: {msg}");
        InputError::EXIT_CODE
    };
    if let Some(flag) = progressive_flag(args) {
        return usage(format!(
            "{flag} cannot be combined with --crop, --tiles, --sample-range, --stats or \
             --debug-pixel (those render one fixed sample range in one pass)"
        ));
    }
    let job = RenderJob::new(&loaded.scene, &loaded.integrator, seed);
    let samples = args.split.samples(args.spp.unwrap_or(loaded.spp));
    if let Some(n) = args
        .spp
        .filter(|n| args.split.sample_range.is_some() && samples.end > *n)
    {
        return usage(format!(
            "--sample-range {}..{} goes past --spp {n}, the render it is a part of",
            samples.start, samples.end
        ));
    }
    let opts = RenderOptions {
        threads,
        tile_size: args.tile_size,
        pixels: args.split.selection(),
    };
    let spp = samples.end - samples.start;
    let part = match args.split.part_info(loaded, &job, samples.clone(), &opts) {
        Ok(p) => p,
        Err(e) => return usage(e),
    };
    if let Some(dp) = args.probe.debug_pixel {
        return tessera_lab::debug_pixel::run(loaded, &job, samples, dp);
    }
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(1)
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} tiles {elapsed_precise} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let start = Instant::now();
    let fb = render_maybe_stats(
        args.probe.stats,
        &job,
        samples,
        &opts,
        &mut |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        },
    );
    bar.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    let mut code = 0;
    // Whole-image outputs take the overlays (PNG only); a split render's outputs are parts or
    // crops of the image, which a label or grid drawn for the whole image would not fit.
    let decor = Decor::new(args, loaded);
    for o in &args.outputs {
        let written = match part {
            None => decor.write(o, &fb, secs),
            Some(_) => write_render_output(o, &fb, part.as_ref()),
        };
        if let Err(e) = written {
            eprintln!("error: {e}");
            code = 1;
        }
    }
    let samples: f64 = fb.pixels.iter().map(|p| (p.count + p.dropped) as f64).sum();
    if !args.quiet || code != 0 {
        eprintln!(
            "{}x{} at {spp} spp in {secs:.2} s ({:.2} M samples/s, {threads} threads); {} non-finite samples dropped",
            fb.width,
            fb.height,
            samples / secs.max(1e-9) / 1e6,
            fb.dropped()
        );
    }
    code
}

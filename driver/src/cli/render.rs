//! `tessera render`: load, render on worker threads, write every requested output.
use crate::error::InputError;
use crate::image_io::{write_image, Format, RgbImage};
use crate::render::{render, RenderOptions};
use crate::scene::load_scene;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `tessera render`.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// The scene file (Mitsuba 3 or Nori XML).
    pub scene: PathBuf,
    /// Output image; the extension picks the format (.exr, .pfm, .png). May be repeated.
    #[arg(short = 'o', long = "output", required = true)]
    pub outputs: Vec<PathBuf>,
    /// Samples per pixel (default: the scene's sampler).
    #[arg(long)]
    pub spp: Option<u64>,
    /// Worker threads (default: all cores). The image does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Seed of every random stream (default: the sampler's `seed`, else 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Integrator name (path, path_mis, path_half, path_ems, path_mats, direct, direct_ems,
    /// direct_mats, direct_mis); keeps the file's max_depth etc.
    #[arg(long)]
    pub integrator: Option<String>,
    /// Sampler (independent, zsobol), overriding the scene file.
    #[arg(long)]
    pub sampler: Option<String>,
    /// Longest path (-1 = unbounded), overriding the scene file.
    #[arg(long, allow_hyphen_values = true)]
    pub max_depth: Option<i64>,
    /// Tile edge in pixels. The image does not depend on it.
    #[arg(long, default_value_t = 32)]
    pub tile_size: u32,
    /// Override a scene `<default>`: -D name=value.
    #[arg(short = 'D', value_parser = super::parse_define)]
    pub defines: Vec<(String, String)>,
    /// No progress bar.
    #[arg(short, long)]
    pub quiet: bool,
}

fn usage(msg: String) -> i32 {
    eprintln!("error: {msg}");
    InputError::EXIT_CODE
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
    let mut loaded = match load_scene(&args.scene, &args.defines) {
        Ok(l) => l,
        Err(e) => return usage(e.to_string()),
    };
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    if let Err(e) = loaded.set_integrator(args.integrator.as_deref(), args.max_depth) {
        return usage(e);
    }
    let spp = args.spp.unwrap_or(loaded.spp);
    if let Err(e) = loaded.set_sampler(args.sampler.as_deref(), spp) {
        return usage(e);
    }
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if threads == 0 {
        return usage("--threads must be at least 1".into());
    }
    let opts = RenderOptions {
        samples: 0..spp,
        threads,
        tile_size: args.tile_size,
        seed: args.seed.unwrap_or(loaded.seed),
    };
    let scene = &loaded.scene;
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
    let fb = render(scene, &loaded.integrator, &opts, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    let img = RgbImage {
        width: fb.width,
        height: fb.height,
        data: fb.rgb(),
    };
    let mut code = 0;
    for o in &args.outputs {
        if let Err(e) = write_image(o, &img) {
            eprintln!("error: {e}");
            code = 1;
        }
    }
    let samples = spp as f64 * fb.width as f64 * fb.height as f64;
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

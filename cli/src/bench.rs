//! `tessera bench`: error against time for one or more integrators, or (`--plot-only`) just the
//! plot of an existing report, e.g. one with Mitsuba 3 rows appended by
//! `scripts/mitsuba_bench.py`. By default each curve follows the protocol of
//! `bench_protocol.rs` (whole renders from 64 spp until one takes 5 s, the efficiency of the
//! last); `--waves` and `--fresh` measure waves of 1, 2, 4, ... spp instead (see
//! `tessera_lab::bench`).
use crate::bench_protocol::{efficiency_line, run_protocol, ProtocolCurve, ProtocolLimits};
use clap::Args;
use std::path::{Path, PathBuf};
use tessera::image_io::{read_image, Format};
use tessera::render::RenderOptions;
use tessera_core::adaptive::AdaptiveParams;
use tessera_core::render::RenderJob;
use tessera_lab::bench::fresh::{fresh_name, run_fresh};
use tessera_lab::bench::mean::mean_curve;
use tessera_lab::bench::plot::write_plot;
use tessera_lab::bench::ratio::{ratio, Ratio};
use tessera_lab::bench::repeat::fastest_curve;
use tessera_lab::bench::{curves, read_csv, run_waves, time_to_target, write_csv, Row, WaveLimits};
use tessera_scene::load_scene;

/// Arguments of `tessera bench`.
#[derive(Args, Debug, Clone)]
pub struct BenchArgs {
    /// The scene file (Mitsuba 3 or Nori XML).
    #[arg(required_unless_present = "plot_only")]
    pub scene: Option<PathBuf>,
    /// The converged reference image (EXR or PFM, the scene's size).
    #[arg(long, required_unless_present = "plot_only")]
    pub reference: Option<PathBuf>,
    /// Integrators to measure, comma separated (default: the scene file's); `NAME+reuse` is the
    /// path tracer NAME with path reuse.
    #[arg(long, value_delimiter = ',')]
    pub integrators: Vec<String>,
    /// Samplers to measure, comma separated (independent, zsobol; default: the scene file's).
    /// Each integrator is measured with each sampler; zsobol is set up for --max-spp samples
    /// (with --fresh, for each wave's count).
    #[arg(long, value_delimiter = ',')]
    pub sampler: Vec<String>,
    /// Measure waves of 1, 2, 4, ... spp added to one image (each row the time so far), instead
    /// of the protocol's whole renders from --min-spp until one takes --min-seconds.
    #[arg(long, conflicts_with = "fresh")]
    pub waves: bool,
    /// The protocol: the first render's samples per pixel.
    #[arg(long, default_value_t = 64)]
    pub min_spp: u64,
    /// The protocol: stop at the first render (load included) that takes this many seconds,
    /// then render its count once more and keep the faster.
    #[arg(long, default_value_t = 5.0)]
    pub min_seconds: f64,
    /// Waves (--waves, --fresh): stop a curve before a wave that would end after this many
    /// seconds.
    #[arg(long, default_value_t = 60.0)]
    pub max_seconds: f64,
    /// Stop a curve at this many samples per pixel.
    #[arg(long, default_value_t = 1 << 20)]
    pub max_spp: u64,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Seed (default: the sampler's `seed`, else 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Measure each curve with this many seeds (the seed, the seed + 1, ...) and report their
    /// wave-by-wave mean (seconds, relMSE, MSE, MAE), which estimates the expected error
    /// better than one seed; `--max-seconds` applies to each seed's run.
    #[arg(long, default_value_t = 1)]
    pub seeds: u64,
    /// Render each seed's curve this many times and keep each wave's least time (the images
    /// must be the same every time): on a shared machine, the fastest run estimates the time
    /// the work takes better than one run, most of all in the first, short waves.
    #[arg(long, default_value_t = 1)]
    pub repeats: u64,
    /// Longest path (-1 = unbounded), overriding the scene file.
    #[arg(long, allow_hyphen_values = true)]
    pub max_depth: Option<i64>,
    /// Tile edge in pixels (the image bits do not depend on it). Default: `render`'s 32 for the
    /// protocol; 16 for waves, whose images are small (128x128 is 16 tiles of 32) and first
    /// waves short, so finer tiles leave the threads less idle at each wave's end.
    #[arg(long)]
    pub tile_size: Option<u32>,
    /// The relMSEs whose time to reach is printed per curve, comma separated (the plot marks
    /// the first).
    #[arg(long, value_delimiter = ',', default_value = "0.01")]
    pub target_relmse: Vec<f64>,
    /// Also print each curve's time to target as a ratio to this curve's (its label as printed,
    /// e.g. `mitsuba-llvm_ad_rgb:path`, or the start of one label): `0.77x`, or a bound (`<=`,
    /// `>=`) where one of the two stopped short of the target or reached it at its first wave.
    #[arg(long)]
    pub ratio_to: Option<String>,
    /// Override a scene `<default>`: -D name=value.
    #[arg(short = 'D', value_parser = super::define::parse_define)]
    pub defines: Vec<(String, String)>,
    /// The CSV report to write.
    #[arg(short = 'o', long = "output", required_unless_present = "plot_only")]
    pub output: Option<PathBuf>,
    /// Also draw the log-log plot of relMSE against seconds to this PNG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Render nothing: read this report and draw `--plot` from it.
    #[arg(long, requires = "plot", conflicts_with_all = ["scene", "reference", "output"])]
    pub plot_only: Option<PathBuf>,
    /// Title of the plot (default: the scene or report file name).
    #[arg(long)]
    pub title: Option<String>,
    /// No line per wave.
    #[arg(short, long)]
    pub quiet: bool,
    /// Also measure each curve with adaptive sampling (after 2 samples in every pixel, each
    /// wave's samples go where the relative variance is highest); its curves are named
    /// `NAME (SAMPLER+adaptive)`.
    #[arg(long)]
    pub adaptive: bool,
    /// Measure only the adaptive curves (implies --adaptive).
    #[arg(long)]
    pub adaptive_only: bool,
    /// Render every wave's image afresh, with the sampler set up for that wave's sample count
    /// (as a render with that `sample_count` does, adaptive ones as `render --adaptive` does,
    /// and as Mitsuba's bench script does), instead of continuing one sequence set up for
    /// --max-spp; a row's time is then that render's alone. Curves are named
    /// `NAME (SAMPLER+fresh)`; a curve costs about twice as long.
    #[arg(long)]
    pub fresh: bool,
}

fn usage(msg: impl std::fmt::Display) -> i32 {
    eprintln!("error: {msg}");
    tessera_scene::error::InputError::EXIT_CODE
}

fn file_name(p: &Path) -> String {
    p.file_name().map_or_else(
        || p.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The curve `--ratio-to` names: the one whose label is `name`, else the only one whose label
/// starts with it.
fn peer_curve<'a>(all: &'a [(String, Vec<Row>)], name: &str) -> Result<&'a [Row], String> {
    if let Some((_, c)) = all.iter().find(|(label, _)| label == name) {
        return Ok(c);
    }
    let starts: Vec<_> = all.iter().filter(|(l, _)| l.starts_with(name)).collect();
    match starts.as_slice() {
        [(_, c)] => Ok(c),
        [] => Err(format!(
            "--ratio-to {name}: no such curve (curves: {})",
            all.iter()
                .map(|(l, _)| l.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )),
        _ => Err(format!(
            "--ratio-to {name}: names several curves ({})",
            starts
                .iter()
                .map(|(l, _)| l.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Prints each curve's time to reach each target relMSE, and with `ratio_to` its ratio to that
/// curve's.
fn print_times(rows: &[Row], targets: &[f64], ratio_to: Option<&str>) -> Result<(), String> {
    let all = curves(rows);
    let peer = ratio_to.map(|n| peer_curve(&all, n)).transpose()?;
    for &target in targets {
        for (name, c) in &all {
            let threads = c.first().map_or(0, |r| r.threads);
            let mut line = format!(
                "{name} ({threads} threads): time to relMSE {target}: {}",
                time_to_target(c, target)
            );
            if let (Some(p), Some(pn)) = (peer, ratio_to) {
                if !std::ptr::eq(p, c.as_slice()) {
                    line.push_str(&match ratio(c, p, target) {
                        Ratio::Unknown => format!(" (ratio to {pn} unknown)"),
                        r => format!(" ({r} {pn})"),
                    });
                }
            }
            println!("{line}");
        }
    }
    Ok(())
}

/// Runs the command; returns the exit code.
pub fn run(args: &BenchArgs) -> i32 {
    if let Some(p) = &args.plot {
        if Format::from_path(p) != Some(Format::Png) {
            return usage(format!("{}: the plot must be a .png file", p.display()));
        }
    }
    if let Some(t) = args
        .target_relmse
        .iter()
        .find(|t| !(**t > 0.0 && t.is_finite()))
    {
        return usage(format!("--target-relmse must be positive, found {t}"));
    }
    if let Some(csv) = &args.plot_only {
        return plot_only(args, csv);
    }
    let (Some(scene_path), Some(ref_path), Some(_)) = (&args.scene, &args.reference, &args.output)
    else {
        return usage("give SCENE, --reference and -o (or --plot-only REPORT --plot PNG)");
    };
    if args.max_seconds.is_nan() || args.max_seconds <= 0.0 {
        return usage(format!(
            "--max-seconds must be positive, found {}",
            args.max_seconds
        ));
    }
    if args.max_spp == 0 {
        return usage("--max-spp must be at least 1");
    }
    if args.seeds == 0 {
        return usage("--seeds must be at least 1");
    }
    if args.repeats == 0 {
        return usage("--repeats must be at least 1");
    }
    let protocol = !(args.waves || args.fresh);
    let tile_size = args.tile_size.unwrap_or(if protocol { 32 } else { 16 });
    if tile_size == 0 || tile_size > 4096 {
        return usage(format!(
            "--tile-size must be between 1 and 4096, found {tile_size}"
        ));
    }
    if protocol {
        if args.adaptive || args.adaptive_only || args.seeds > 1 || args.repeats > 1 {
            return usage(
                "--adaptive, --seeds and --repeats measure waves: add --waves or --fresh (the \
                 protocol renders each count afresh and keeps the faster of two runs)",
            );
        }
        if args.min_spp == 0 {
            return usage("--min-spp must be at least 1");
        }
        if !(args.min_seconds >= 0.0 && args.min_seconds.is_finite()) {
            return usage(format!(
                "--min-seconds must be finite and not negative, found {}",
                args.min_seconds
            ));
        }
    }
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if threads == 0 {
        return usage("--threads must be at least 1");
    }
    let reference = match read_image(ref_path) {
        Ok(r) => r,
        Err(e) => return usage(e),
    };
    let mut loaded = match load_scene(scene_path, &args.defines) {
        Ok(l) => l,
        Err(e) => return usage(e),
    };
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let (w, h) = (loaded.scene.camera.width, loaded.scene.camera.height);
    if (reference.width, reference.height) != (w, h) {
        return usage(format!(
            "{}: the reference is {}x{} but the scene renders {w}x{h}",
            ref_path.display(),
            reference.width,
            reference.height
        ));
    }
    let names: Vec<String> = if args.integrators.is_empty() {
        vec![loaded.integrator_spec.name.clone()]
    } else {
        args.integrators.clone()
    };
    let samplers: Vec<Option<&str>> = if args.sampler.is_empty() {
        vec![None]
    } else {
        args.sampler.iter().map(|s| Some(s.as_str())).collect()
    };
    // Check every name before spending time on any.
    for n in &names {
        if let Err(e) = loaded.set_integrator(Some(n), args.max_depth) {
            return usage(e);
        }
    }
    for s in &samplers {
        if let Err(e) = loaded.set_sampler(*s, args.max_spp) {
            return usage(e);
        }
    }
    let opts = RenderOptions {
        threads,
        tile_size,
        pixels: Default::default(),
    };
    if protocol {
        return run_protocol_curves(
            args,
            scene_path,
            &reference,
            &names,
            &samplers,
            &opts,
            (w, h),
        );
    }
    let first_seed = args.seed.unwrap_or(loaded.seed);
    let limits = WaveLimits {
        max_seconds: args.max_seconds,
        max_spp: args.max_spp,
    };
    let params = AdaptiveParams::default();
    let modes: Vec<Option<&AdaptiveParams>> = match (args.adaptive, args.adaptive_only) {
        (_, true) => vec![Some(&params)],
        (true, false) => vec![None, Some(&params)],
        (false, false) => vec![None],
    };
    let mut rows = Vec::new();
    let mut jobs = Vec::new();
    for n in &names {
        for s in &samplers {
            for a in &modes {
                jobs.push((n, *s, *a));
            }
        }
    }
    for (n, s, adaptive) in jobs {
        if let Err(e) = loaded.set_integrator(Some(n), args.max_depth) {
            return usage(e);
        }
        if let Err(e) = loaded.set_sampler(s, args.max_spp) {
            return usage(e);
        }
        let sampler = match (adaptive, args.fresh) {
            (a, true) => fresh_name(loaded.scene.sampler, a.is_some()),
            (Some(_), false) => format!("{}+adaptive", loaded.scene.sampler.name()),
            (None, false) => loaded.scene.sampler.name().to_string(),
        };
        let mut runs = Vec::new();
        for k in 0..args.seeds {
            let seed = first_seed.wrapping_add(k);
            let label = format!("{n} ({sampler}");
            match fastest_of_repeats(
                args,
                &mut loaded,
                n,
                &label,
                seed,
                &opts,
                &reference,
                limits,
                adaptive,
            ) {
                Ok(r) => runs.push(r),
                Err(e) => {
                    eprintln!("error: {e}");
                    return 1;
                }
            }
        }
        match mean_curve(&runs) {
            Some(r) => rows.extend(r),
            None => {
                eprintln!("error: {n} ({sampler}): the seeds' waves do not line up");
                return 1;
            }
        }
    }
    finish(args, scene_path, &rows, threads, (w, h))
}

/// Prints the times to target, writes the report and the plot; the exit code.
fn finish(
    args: &BenchArgs,
    scene_path: &Path,
    rows: &[Row],
    threads: usize,
    (w, h): (u32, u32),
) -> i32 {
    // A bad --ratio-to is found only now, when the curves exist; the measurements are still
    // written, and the exit code says the command was misused.
    let mut code = 0;
    if let Err(e) = print_times(rows, &args.target_relmse, args.ratio_to.as_deref()) {
        code = usage(e);
    }
    let output = args.output.as_deref().expect("checked by run");
    if let Err(e) = write_csv(output, rows) {
        eprintln!("error: {e}");
        code = 1;
    }
    if let Some(p) = &args.plot {
        let title = args
            .title
            .clone()
            .unwrap_or_else(|| format!("{} ({w}x{h}, {threads} threads)", file_name(scene_path)));
        if let Err(e) = write_plot(p, rows, &title, args.target_relmse.first().copied()) {
            eprintln!("error: {e}");
            code = 1;
        }
    }
    code
}

/// The protocol's curves, one per integrator and sampler; then [`finish`].
fn run_protocol_curves(
    args: &BenchArgs,
    scene_path: &Path,
    reference: &tessera::image_io::RgbImage,
    names: &[String],
    samplers: &[Option<&str>],
    opts: &RenderOptions,
    size: (u32, u32),
) -> i32 {
    let limits = ProtocolLimits {
        min_spp: args.min_spp,
        min_seconds: args.min_seconds,
        max_spp: args.max_spp,
    };
    let mut rows = Vec::new();
    let mut summary = Vec::new();
    for n in names {
        for s in samplers {
            let curve = ProtocolCurve {
                scene: scene_path,
                defines: &args.defines,
                integrator: n,
                sampler: *s,
                max_depth: args.max_depth,
                seed: args.seed,
            };
            let mut print = |row: &Row| {
                if !args.quiet {
                    eprintln!(
                        "{n} ({}): {:>7} spp {:>9.3} s (load included) {:>7.3} M samples/s  relMSE {:.4e}",
                        row.sampler,
                        row.spp,
                        row.seconds,
                        row.samples_per_second / 1e6,
                        row.errors.relmse
                    );
                }
            };
            match run_protocol(&curve, opts, reference, &limits, &mut print) {
                Ok(r) => {
                    summary.extend(efficiency_line(&r));
                    rows.extend(r);
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    return 1;
                }
            }
        }
    }
    for line in summary {
        println!("{line}");
    }
    finish(args, scene_path, &rows, opts.threads, size)
}

/// One seed's curve: `args.repeats` runs of the waves, each wave keeping its least time
/// ([`fastest_curve`]); a line per wave unless `--quiet`. `label` is the line's prefix, e.g.
/// `path_mis (zsobol` (the seed and run are added, then the closing parenthesis).
#[allow(clippy::too_many_arguments)]
fn fastest_of_repeats(
    args: &BenchArgs,
    loaded: &mut tessera_scene::LoadedScene,
    integrator: &str,
    label: &str,
    seed: u64,
    opts: &RenderOptions,
    reference: &tessera::image_io::RgbImage,
    limits: WaveLimits,
    adaptive: Option<&AdaptiveParams>,
) -> Result<Vec<Row>, String> {
    let mut runs = Vec::new();
    for rep in 0..args.repeats {
        let mut note = String::new();
        if args.seeds > 1 {
            note.push_str(&format!(" seed {seed}"));
        }
        if args.repeats > 1 {
            note.push_str(&format!(" run {}", rep + 1));
        }
        let mut print = |row: &Row| {
            if !args.quiet {
                eprintln!(
                    "{label}{note}): {:>7} spp {:>9.3} s {:>7.3} M samples/s  relMSE {:.4e}  RMSE {:.4e}  MAE {:.4e}",
                    row.spp,
                    row.seconds,
                    row.samples_per_second / 1e6,
                    row.errors.relmse,
                    row.errors.rmse,
                    row.errors.mae
                );
            }
        };
        let r = if args.fresh {
            run_fresh(
                &mut loaded.scene,
                &loaded.integrator,
                seed,
                integrator,
                opts,
                reference,
                limits,
                adaptive,
                &mut print,
            )
        } else {
            let job = RenderJob::new(&loaded.scene, &loaded.integrator, seed);
            let (r, _) = run_waves(
                &job, integrator, opts, reference, limits, adaptive, &mut print,
            );
            r
        };
        runs.push(r);
    }
    fastest_curve(&runs)
}

fn plot_only(args: &BenchArgs, csv: &Path) -> i32 {
    let Some(png) = &args.plot else {
        return usage("--plot-only needs --plot OUT.png");
    };
    let rows = match read_csv(csv) {
        Ok(r) => r,
        Err(e) => return usage(e),
    };
    if let Err(e) = print_times(&rows, &args.target_relmse, args.ratio_to.as_deref()) {
        return usage(e);
    }
    let title = args.title.clone().unwrap_or_else(|| file_name(csv));
    match write_plot(png, &rows, &title, args.target_relmse.first().copied()) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    }
}

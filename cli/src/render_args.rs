//! The arguments of `tessera render`, shared by the command and the files that decorate and
//! write its outputs.
use clap::Args;
use std::path::PathBuf;

/// Arguments of `tessera render`.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// The scene file (Mitsuba 3 or Nori XML).
    pub scene: PathBuf,
    /// Output image; the extension picks the format (.exr, .pfm, .png). May be repeated.
    #[arg(short = 'o', long = "output", required_unless_present = "debug_pixel")]
    pub outputs: Vec<PathBuf>,
    /// Samples per pixel (default: the scene's sampler, or the resumed checkpoint's target);
    /// zsobol's pixel blocks are set up for it (a resumed render keeps its first run's).
    #[arg(long, conflicts_with = "forever")]
    pub spp: Option<u64>,
    /// Time budget in seconds: render passes until it is spent (with --spp, whichever first).
    #[arg(long, conflicts_with = "forever")]
    pub time: Option<f64>,
    /// Render until interrupted (Ctrl-C or SIGTERM), writing the outputs on the way out.
    #[arg(long)]
    pub forever: bool,
    /// Write the current average to every output (and the checkpoint) this often, in seconds.
    #[arg(long)]
    pub write_every: Option<f64>,
    /// Checkpoint file, written at every --write-every, at the end and on interrupt.
    #[arg(long)]
    pub checkpoint: Option<PathBuf>,
    /// Continue the render saved in this checkpoint (and keep checkpointing to it unless
    /// --checkpoint names another file).
    #[arg(long)]
    pub resume: Option<PathBuf>,
    /// Scale the film's width and height (e.g. 0.25 for a quick preview; at least 1 pixel).
    #[arg(long)]
    pub resolution_scale: Option<f64>,
    /// Label PNG outputs with integrator, sampler, spp, time and resolution (EXR/PFM untouched).
    #[arg(long)]
    pub overlay: bool,
    /// Draw the tile grid on PNG outputs.
    #[arg(long)]
    pub overlay_grid: bool,
    /// Draw a rectangle x0,y0,x1,y1 (pixels) on PNG outputs.
    #[arg(long, value_parser = tessera::overlay::parse_crop)]
    pub overlay_crop: Option<[u32; 4]>,
    /// Worker threads (default: all cores). The image does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Seed of every random stream (default: the sampler's `seed`, else 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Integrator name (path, path_mis, path_half, path_ems, path_mats, direct, direct_ems,
    /// direct_mats, direct_mis; a path tracer's name with `+reuse` for path reuse); keeps the
    /// file's max_depth etc.
    #[arg(long)]
    pub integrator: Option<String>,
    /// Sampler (independent, zsobol), overriding the scene file.
    #[arg(long)]
    pub sampler: Option<String>,
    /// Apply the film's reconstruction filter by importance sampling it, as pbrt-v4 does: each
    /// pixel's samples are its own (and unbiased also for filters with negative lobes). The
    /// default splats every sample over the pixels the filter reaches, as Mitsuba 3 does, which
    /// at equal samples gives a lower error. The `box` filter is the same either way.
    #[arg(long)]
    pub filter_sampling: bool,
    /// Longest path (-1 = unbounded), overriding the scene file.
    #[arg(long, allow_hyphen_values = true)]
    pub max_depth: Option<i64>,
    /// Tile edge in pixels. The image does not depend on it.
    #[arg(long, default_value_t = 32)]
    pub tile_size: u32,
    /// Override a scene `<default>`: -D name=value.
    #[arg(short = 'D', value_parser = super::define::parse_define)]
    pub defines: Vec<(String, String)>,
    /// Render a Nori-vocabulary file as `nori` (the default, also Mitsuba 3's image) or
    /// `wakame` (the image mirrored left to right, as Wakame's camera draws it) renders it,
    /// whatever the file's `<?tessera dialect="..."?>` says.
    #[arg(long, value_parser = tessera_scene::Dialect::parse)]
    pub dialect: Option<tessera_scene::Dialect>,
    /// No progress bar.
    #[arg(short, long)]
    pub quiet: bool,
    /// Adaptive sampling: after 2 samples in every pixel, passes doubling the mean sample count
    /// send each pass's samples where the relative variance is highest; --spp is then the mean
    /// over pixels. Consistent, not unbiased (see docs/guide/adaptive-sampling.md).
    #[arg(long)]
    pub adaptive: bool,
    /// Stop at the first power of two spp (with --adaptive: doubling of the mean) whose relative
    /// MSE, estimated from the two halves of the samples, is at most this (e.g. 1e-3; checked
    /// from 16 spp on). Without --spp there is no sample limit.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "forever")]
    pub target_error: Option<f64>,
    /// Render a piece of the image (a part, for `tessera merge`).
    #[command(flatten)]
    pub split: super::split_args::SplitArgs,
    /// `--stats`, `--debug-pixel`.
    #[command(flatten)]
    pub probe: super::probe_args::ProbeArgs,
}

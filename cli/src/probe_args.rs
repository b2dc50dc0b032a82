//! Flags of `tessera render` that observe the render: `--stats` and `--debug-pixel`.
use clap::Args;
use tessera_lab::debug_pixel::{parse_debug_pixel, DebugPixel};

/// Observation flags, flattened into `tessera render`'s arguments.
#[derive(Args, Debug, Clone, Default)]
pub struct ProbeArgs {
    /// Print counts of the work done after the render (rays by kind, BSDF and emitter samples,
    /// MIS weights, environment lookups, hits by primitive kind...). The image is the same bits.
    #[arg(long)]
    pub stats: bool,
    /// Render only pixel x,y (all its samples, or only sample index `sample`) and print each
    /// sample's path and value instead of writing images.
    #[arg(long, value_name = "X,Y[,SAMPLE]", value_parser = parse_debug_pixel)]
    pub debug_pixel: Option<DebugPixel>,
}

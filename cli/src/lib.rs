//! The `tessera` command line as a library: argument definitions and one module per subcommand
//! (`src/main.rs` is the binary). Tests call the subcommands in-process through it.
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
pub mod bench;
pub mod bench_protocol;
pub mod compare;
pub(crate) mod decor;
pub mod define;
pub mod info;
pub mod merge;
pub mod plugins;
pub(crate) mod probe_args;
pub mod render;
pub(crate) mod render_args;
pub mod render_layers;
pub mod render_once;
pub(crate) mod split_args;
pub mod test;
pub mod view;

use clap::{Parser, Subcommand};

/// Tessera: a physically based Monte Carlo path tracer.
#[derive(Parser, Debug)]
#[command(name = "tessera", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene file to one or more images.
    Render(render::RenderArgs),
    /// Run a Nori-style test file (`ttest` with scenes or BSDFs, `chi2test`) and report each case.
    Test(test::TestArgs),
    /// Measure error against time in waves of 1, 2, 4, ... spp against a reference image; write
    /// a CSV report and a log-log plot (or plot an existing report).
    Bench(bench::BenchArgs),
    /// Compare an image with a reference: means, RMSE, relMSE, MAE, largest difference; text or
    /// JSON, optionally a false-colour difference PNG.
    Compare(compare::CompareArgs),
    /// Print the plugin reference: every plugin a scene file can name, with its parameters
    /// (or only the plugins called NAME).
    Plugins(plugins::PluginsArgs),
    /// Load a scene without rendering it and print what it holds (settings, shapes, primitives,
    /// BSDFs, emitters, textures and their memory, the acceleration structure, warnings).
    Info(info::InfoArgs),
    /// Serve a live view of a progressive render on a local web page, where the camera can be
    /// moved, materials and the integrator edited, and the image and edited scene saved.
    View(view::ViewArgs),
    /// Assemble part files (from a render with --crop, --tiles or --sample-range) into one image.
    Merge(merge::MergeArgs),
}

//! `tessera render` of a scene whose integrator adds image channels (`aov`, `moment`): after
//! the colour render, each layer of channels is rendered with the same seed, sampler and sample
//! count, or taken from the colour where its integrator is the colour's or the colour's own pass
//! gathered it (a second moment, surface variables; see `tessera::layers`), and EXR outputs get
//! every channel under Mitsuba 3's names.
//! PNG and PFM outputs hold the colour only (one warning says so). Renders that stop on a time
//! budget, an error target or a signal, resume, adapt or split do not know the final sample
//! count of every pixel in advance, so they are refused with these integrators.
use super::decor::Decor;
use super::render_args::RenderArgs;
use super::render_once::progressive_flag;
use tessera::image_io::Format;
use tessera::layers::{self, render_layers, rgb_channels, write_channels_exr};
use tessera::render::{Framebuffer, RenderOptions};
use tessera_core::splat::Footprint;
use tessera_scene::LoadedScene;

/// Refuses the flags a render with extra channels does not support (one line).
pub(crate) fn check_args(args: &RenderArgs, loaded: &LoadedScene) -> Result<(), String> {
    if loaded.integrator_spec.layers.is_empty() {
        return Ok(());
    }
    let flag = progressive_flag(args).or_else(|| {
        [
            (args.split.is_split(), "--crop, --tiles or --sample-range"),
            (args.probe.stats, "--stats"),
            (args.probe.debug_pixel.is_some(), "--debug-pixel"),
        ]
        .into_iter()
        .find_map(|(given, name)| given.then_some(name))
    });
    match flag {
        Some(flag) => Err(format!(
            "{}: {flag} cannot be combined with an integrator that writes extra channels (aov, \
             moment); render them with --spp",
            args.scene.display()
        )),
        None => Ok(()),
    }
}

/// Whether the colour render of `args` gathers its samples' XYZ squares: a second moment of the
/// colour's integrator is among the layers and an EXR output will hold it.
pub(crate) fn wants_squares(args: &RenderArgs, loaded: &LoadedScene) -> bool {
    wants_exr(args) && layers::wants_squares(&loaded.integrator_spec.layers)
}

/// The surface variables the colour render of `args` gathers in its pass: those among the
/// layers when an EXR output will hold them and the colour's integrator does not reuse paths
/// (whose samples' values depend on their group; the variables are then rendered after).
pub(crate) fn gathered_aovs(
    args: &RenderArgs,
    loaded: &LoadedScene,
) -> Vec<tessera_core::integrator::AovIntegrator> {
    if !wants_exr(args) || tessera_core::render::reuses(&loaded.integrator) {
        return Vec::new();
    }
    // Renders with extra channels take a fixed count (`check_args`).
    let spp = args.spp.unwrap_or(loaded.spp);
    let mut list = layers::gathered_aovs(&loaded.integrator_spec.layers, spp);
    let camera = &loaded.scene.camera;
    let pixels = camera.width as usize * camera.height as usize;
    let reach = loaded.scene.splat.as_ref().map(Footprint::reach);
    let each = Framebuffer::bytes_for(pixels, reach).max(1);
    list.truncate(GATHER_BUDGET_BYTES / each);
    list
}

/// Memory the colour's pass may add to gather surface variables (each as large as the colour's
/// own sums: 400 bytes a pixel with a Gaussian filter). The variables beyond it are rendered
/// after the colour, one at a time, with the same bits.
const GATHER_BUDGET_BYTES: usize = 1 << 30;

/// Whether an output is an EXR file (the only format that holds the extra channels).
fn wants_exr(args: &RenderArgs) -> bool {
    args.outputs
        .iter()
        .any(|o| Format::from_path(o) == Some(Format::Exr))
}

/// Renders the extra channels for the samples `fb` holds (every pixel the same count) and
/// writes every output.
pub(super) fn write(
    args: &RenderArgs,
    loaded: &LoadedScene,
    fb: &Framebuffer,
    seed: u64,
    opts: &RenderOptions,
    decor: &Decor,
    seconds: f64,
) -> Result<(), String> {
    let spp = fb.pixels.first().map_or(0, |p| p.count + p.dropped);
    let layers = &loaded.integrator_spec.layers;
    let rgb = fb.rgb();
    let extra = match wants_exr(args) {
        true => render_layers(&loaded.scene, layers, seed, 0..spp, opts, &rgb, Some(fb))?,
        false => Vec::new(),
    };
    let mut warned = false;
    for o in &args.outputs {
        if Format::from_path(o) == Some(Format::Exr) {
            let mut channels = rgb_channels(&rgb);
            channels.extend(extra.iter().cloned());
            write_channels_exr(o, fb.width, fb.height, &channels, opts.threads)?;
        } else {
            if !warned {
                eprintln!(
                    "warning: {}: the {} extra channels of the integrator are written only to \
                     .exr outputs",
                    o.display(),
                    layers.iter().map(|l| l.names.len()).sum::<usize>()
                );
                warned = true;
            }
            decor.write(o, fb, seconds)?;
        }
    }
    Ok(())
}

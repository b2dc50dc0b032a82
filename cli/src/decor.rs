//! What `tessera render` draws on its PNG outputs (`--overlay`, `--overlay-grid`,
//! `--overlay-crop`) and how it writes an image of the current average.
use super::render_args::RenderArgs;
use std::path::Path;
use tessera::image_io::{to_srgb8, write_image, write_png8, Format, RgbImage};
use tessera::overlay::{self, Overlay};
use tessera::progressive::spp_range;
use tessera::render::Framebuffer;
use tessera_scene::LoadedScene;

/// What `--overlay*` asks to draw on PNG outputs.
pub(super) struct Decor {
    /// First label line (integrator and sampler); `None` without `--overlay`.
    label: Option<String>,
    grid: Option<u32>,
    crop: Option<[u32; 4]>,
}

impl Decor {
    /// The overlays the arguments ask for.
    pub(super) fn new(args: &RenderArgs, loaded: &LoadedScene) -> Decor {
        let spec = &loaded.integrator_spec;
        let sampler = loaded.scene.sampler.name();
        let label = match (spec.name.starts_with("path"), spec.max_depth) {
            (true, Some(d)) => format!("{}, max_depth {d}, {sampler} sampler", spec.name),
            (true, None) => format!("{}, unbounded depth, {sampler} sampler", spec.name),
            (false, _) => format!("{}, {sampler} sampler", spec.name),
        };
        Decor {
            label: args.overlay.then_some(label),
            grid: args.overlay_grid.then_some(args.tile_size),
            crop: args.overlay_crop,
        }
    }

    /// The overlay for an image of `fb` rendered in `seconds`.
    fn overlay(&self, fb: &Framebuffer, seconds: f64) -> Overlay {
        let lines = self.label.iter().fold(Vec::new(), |mut v, l| {
            v.push(l.clone());
            v.push(format!(
                "{} spp, {seconds:.1} s, {}x{}",
                spp_text(fb),
                fb.width,
                fb.height
            ));
            v
        });
        Overlay {
            lines,
            grid: self.grid,
            crop: self.crop,
        }
    }

    /// Writes the average of `fb` to `path`, with the overlays when it is a PNG.
    pub(super) fn write(&self, path: &Path, fb: &Framebuffer, seconds: f64) -> Result<(), String> {
        let img = RgbImage {
            width: fb.width,
            height: fb.height,
            data: fb.rgb(),
        };
        let ov = self.overlay(fb, seconds);
        let decorated = !ov.lines.is_empty() || ov.grid.is_some() || ov.crop.is_some();
        if decorated && Format::from_path(path) == Some(Format::Png) {
            let mut rgb8 = to_srgb8(&img);
            overlay::apply(&mut rgb8, img.width, img.height, &ov);
            write_png8(path, img.width, img.height, rgb8)
        } else {
            write_image(path, &img)
        }
    }
}

/// The samples per pixel of `fb` as text: `N`, or `LOW-HIGH (mean M)` when pixels differ.
pub(super) fn spp_text(fb: &Framebuffer) -> String {
    match spp_range(fb) {
        (lo, hi) if lo == hi => format!("{lo}"),
        (lo, hi) => {
            let n = (fb.pixels.len() as u64).max(1);
            let taken: u64 = fb.pixels.iter().map(|p| p.count + p.dropped).sum();
            format!("{lo}-{hi} (mean {:.1})", taken as f64 / n as f64)
        }
    }
}

//! The driver as a library: load a scene (from a file or from text), render it on worker
//! threads, get the image. These are thin, documented entry points over [`tessera_scene`] and
//! [`crate::render`], for programs that embed Tessera instead of calling the `tessera` command.
//!
//! ```no_run
//! let scene = tessera::load("scenes/cbox.xml").expect("the scene loads");
//! let image = tessera::render(&scene, &tessera::Options { spp: Some(16), ..Default::default() });
//! tessera::image_io::write_image("cbox.png".as_ref(), &image).expect("the image is written");
//! ```
use crate::image_io::RgbImage;
use crate::render::RenderOptions;
use std::path::Path;
use tessera_core::render::RenderJob;
use tessera_scene::error::InputError;
use tessera_scene::{load_scene, load_scene_str, LoadedScene};

/// A rendered image: linear RGB, row-major, top row first.
pub type Image = RgbImage;

/// How [`render`] renders. `Default` gives: the scene's own sample count and seed, all cores,
/// 32-pixel tiles. The image does not depend on `threads` or `tile_size`.
#[derive(Clone, Debug)]
pub struct Options {
    /// Samples per pixel (`None`: the scene's sampler `sample_count`).
    pub spp: Option<u64>,
    /// Seed of every random stream (`None`: the sampler's `seed`).
    pub seed: Option<u64>,
    /// Worker threads (`None`: all cores).
    pub threads: Option<usize>,
    /// Tile edge in pixels.
    pub tile_size: u32,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            spp: None,
            seed: None,
            threads: None,
            tile_size: 32,
        }
    }
}

/// Loads a scene file (Mitsuba 3 or Nori XML); relative paths in it resolve beside the file.
pub fn load(path: impl AsRef<Path>) -> Result<LoadedScene, InputError> {
    load_scene(path.as_ref(), &[])
}

/// Loads a scene from XML text; relative paths in it resolve against `base_dir`.
pub fn load_str(xml: &str, base_dir: impl AsRef<Path>) -> Result<LoadedScene, InputError> {
    load_scene_str(xml, &base_dir.as_ref().join("<string>.xml"), &[])
}

/// Renders the whole image with the scene's integrator and returns the per-pixel means (the
/// accumulated sums are available through [`crate::render::render`] when needed). The same bits
/// for any thread count and tile size.
pub fn render(scene: &LoadedScene, options: &Options) -> Image {
    let opts = RenderOptions {
        threads: options
            .threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
            .max(1),
        tile_size: options.tile_size.max(1),
        ..Default::default()
    };
    let job = RenderJob::new(
        &scene.scene,
        &scene.integrator,
        options.seed.unwrap_or(scene.seed),
    );
    let samples = 0..options.spp.unwrap_or(scene.spp);
    let fb = crate::render::render(&job, samples, &opts, &mut |_, _| {});
    RgbImage {
        width: fb.width,
        height: fb.height,
        data: fb.rgb(),
    }
}

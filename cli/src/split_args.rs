//! `tessera render` options that render one piece of an image (`--crop`, `--tiles`,
//! `--sample-range`), and writing such a piece: a part file for `.exr` outputs (mergeable with
//! `tessera merge`), the selection's bounding box for `.png` / `.pfm`.
use clap::Args;
use std::ops::Range;
use std::path::Path;
use tessera::image_io::{write_image, Format, RgbImage};
use tessera::render::{Framebuffer, RenderOptions, Tile};
use tessera::split::selection::{parse_crop, parse_sample_range, parse_tile_set};
use tessera::split::{write_part, PartInfo, PixelSelection};
use tessera_core::render::RenderJob;
use tessera_scene::LoadedScene;

/// Render only a piece of the image.
#[derive(Args, Debug, Clone, Default)]
pub struct SplitArgs {
    /// Render only the pixel window [x0, x1) x [y0, y1): --crop x0,y0,x1,y1.
    #[arg(long, value_parser = parse_crop, conflicts_with = "tiles")]
    pub crop: Option<Tile>,
    /// Render only tile set K of N (1-based, e.g. $SLURM_ARRAY_TASK_ID/8): the tiles of the
    /// scanline tile list whose index i has i % N == K - 1.
    #[arg(long, value_parser = parse_tile_set, value_name = "K/N")]
    pub tiles: Option<(u32, u32)>,
    /// Render only the sample indices a..b (a < b) of each pixel, of a render of --spp samples
    /// if given (zsobol's pixel blocks follow that count: give the parts of an N-sample render
    /// --spp N to merge to its bits), else of the scene's sample count.
    #[arg(long, value_parser = parse_sample_range, value_name = "A..B")]
    pub sample_range: Option<Range<u64>>,
}

impl SplitArgs {
    /// The pixels to render.
    pub fn selection(&self) -> PixelSelection {
        match (self.crop, self.tiles) {
            (Some(c), _) => PixelSelection::Crop(c),
            (None, Some((k, n))) => PixelSelection::Tiles { k, n },
            (None, None) => PixelSelection::All,
        }
    }

    /// The sample indices to render, given the samples per pixel otherwise asked for.
    pub fn samples(&self, spp: u64) -> Range<u64> {
        self.sample_range.clone().unwrap_or(0..spp)
    }

    /// Whether only a piece of the image is rendered (outputs are then parts).
    pub(crate) fn is_split(&self) -> bool {
        self.crop.is_some() || self.tiles.is_some() || self.sample_range.is_some()
    }

    /// Checks the selection against the scene and, for a split render, returns what its part
    /// files record: the job's seed, the samples rendered and the final render options (pixels,
    /// tile size).
    pub fn part_info(
        &self,
        loaded: &LoadedScene,
        job: &RenderJob,
        samples: Range<u64>,
        opts: &RenderOptions,
    ) -> Result<Option<PartInfo>, String> {
        let (w, h) = (loaded.scene.camera.width, loaded.scene.camera.height);
        opts.pixels.check(w, h, opts.tile_size)?;
        if !self.is_split() {
            return Ok(None);
        }
        Ok(Some(PartInfo {
            width: w,
            height: h,
            selection: opts.pixels,
            tile_size: opts.tile_size,
            samples,
            seed: job.seed,
            integrator: format!(
                "{:?}, sampler {:?}",
                loaded.integrator_spec, loaded.scene.sampler
            ),
            scene_hash: loaded.source_hash,
        }))
    }
}

/// Writes one output of a render: for a split render (`part` given) a part file if `path` is an
/// `.exr`, else the selection's bounding box as an image; for a whole render the image.
pub(crate) fn write_render_output(
    path: &Path,
    fb: &Framebuffer,
    part: Option<&PartInfo>,
) -> Result<(), String> {
    let Some(info) = part else {
        let img = RgbImage {
            width: fb.width,
            height: fb.height,
            data: fb.rgb(),
        };
        return write_image(path, &img);
    };
    if Format::from_path(path) == Some(Format::Exr) {
        return write_part(path, info, fb);
    }
    let b = info
        .selection
        .bounds(info.width, info.height, info.tile_size)
        .unwrap_or(Tile {
            x0: 0,
            y0: 0,
            x1: fb.width,
            y1: fb.height,
        });
    let mut data = Vec::with_capacity(((b.x1 - b.x0) * (b.y1 - b.y0)) as usize);
    for y in b.y0..b.y1 {
        for x in b.x0..b.x1 {
            data.push(fb.at(x, y).mean());
        }
    }
    let img = RgbImage {
        width: b.x1 - b.x0,
        height: b.y1 - b.y0,
        data,
    };
    write_image(path, &img)
}

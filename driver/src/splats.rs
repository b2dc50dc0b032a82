//! The film's splatted sums (see `core/src/splat.rs`): for each pixel, one running sum per pixel
//! its samples reach, kept beside its own [`PixelAccum`] and carried with it through tiles,
//! passes, checkpoints and part files, so that every one is added to in sample-index order by
//! the one worker that renders its pixel.
use crate::tile::Tile;
use tessera_core::film::PixelAccum;
use tessera_core::glam::Vec2;
use tessera_core::splat::{resolve, stride, Footprint};
use tessera_core::Color;

/// Every pixel's splatted sums, row-major, [`stride`] floats per pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Splats {
    /// How far samples reach: targets at offsets `-reach..=reach` on each axis.
    pub reach: u32,
    /// The sums, pixel after pixel.
    pub sums: Vec<f32>,
}

impl Splats {
    /// Empty sums of reach `reach` for `pixels` pixels.
    pub fn new(reach: u32, pixels: usize) -> Self {
        let sums = vec![0.0; pixels * stride(reach)];
        Splats { reach, sums }
    }

    /// Floats per pixel.
    pub fn stride(&self) -> usize {
        stride(self.reach)
    }

    /// The image of a `width x height` framebuffer holding these sums.
    pub fn resolve(&self, width: u32, height: u32) -> Vec<[f32; 3]> {
        resolve(self.reach, width, height, &self.sums)
    }

    /// The sums of pixel `i` (row-major index).
    pub fn pixel(&self, i: usize) -> &[f32] {
        let s = self.stride();
        &self.sums[i * s..(i + 1) * s]
    }

    /// The sums of pixel `i`, to write.
    pub fn pixel_mut(&mut self, i: usize) -> &mut [f32] {
        let s = self.stride();
        &mut self.sums[i * s..(i + 1) * s]
    }
}

/// What a worker adds a tile's samples to: a copy of the tile's accumulators and, when the scene
/// splats, of their splatted sums, written back into the framebuffer when the tile is done. A
/// worker keeps one and reloads it for each tile, so its buffers are allocated once.
#[derive(Debug)]
pub(crate) struct TileSums<'a> {
    /// The tile's pixels' accumulators, row-major within the tile.
    pub(crate) pixels: Vec<PixelAccum>,
    /// Their splatted sums (empty when the scene does not splat).
    sums: Vec<f32>,
    footprint: Option<&'a Footprint>,
}

impl<'a> TileSums<'a> {
    /// Empty sums, to which samples splat over `footprint`.
    pub(crate) fn new(footprint: Option<&'a Footprint>) -> Self {
        TileSums {
            pixels: Vec::new(),
            sums: Vec::new(),
            footprint,
        }
    }

    /// Replaces the contents with the sums of tile `t` of a `width`-wide image, from `pixels`
    /// and `splats` (whose reach must be that of the footprint).
    pub(crate) fn load(
        &mut self,
        t: &Tile,
        width: u32,
        pixels: &[PixelAccum],
        splats: Option<&Splats>,
    ) {
        self.pixels.clear();
        self.sums.clear();
        for y in t.y0..t.y1 {
            let row = y as usize * width as usize;
            let (a, b) = (row + t.x0 as usize, row + t.x1 as usize);
            self.pixels.extend_from_slice(&pixels[a..b]);
            if let Some(s) = splats {
                self.sums
                    .extend_from_slice(&s.sums[a * s.stride()..b * s.stride()]);
            }
        }
    }

    /// Adds a sample of value `c`, `offset` from its pixel's centre, to the tile's pixel `k`; a
    /// non-finite value is counted as dropped and splats nothing.
    #[inline]
    pub(crate) fn add(&mut self, k: usize, c: Color, offset: Vec2) {
        self.pixels[k].add(c);
        if let Some(f) = self.footprint {
            if c.is_finite() {
                let s = f.stride();
                f.add(&mut self.sums[k * s..(k + 1) * s], offset, c);
            }
        }
    }

    /// Writes the tile's sums back into place.
    pub(crate) fn write(
        &self,
        t: &Tile,
        width: u32,
        pixels: &mut [PixelAccum],
        splats: Option<&mut Splats>,
    ) {
        let tw = (t.x1 - t.x0) as usize;
        let stride = self.footprint.map_or(0, Footprint::stride);
        let mut splats = splats;
        for (row, y) in (t.y0..t.y1).enumerate() {
            let dst = y as usize * width as usize + t.x0 as usize;
            pixels[dst..dst + tw].copy_from_slice(&self.pixels[row * tw..(row + 1) * tw]);
            if let Some(s) = splats.as_deref_mut() {
                let src = &self.sums[row * tw * stride..(row + 1) * tw * stride];
                s.sums[dst * stride..(dst + tw) * stride].copy_from_slice(src);
            }
        }
    }
}

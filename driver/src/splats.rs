//! The film's splatted sums (see `core/src/splat.rs`): for each pixel, one running sum per pixel
//! its samples reach, kept beside its own [`PixelAccum`](tessera_core::film::PixelAccum) and carried with it through tiles,
//! passes, checkpoints and part files, so that every one is added to in sample-index order by
//! the one worker that renders its pixel.
use tessera_core::splat::{resolve, stride};

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

    /// The image of a `width x height` framebuffer holding these sums, its pixels holding
    /// `samples` samples attempted each (row-major; see
    /// [`resolve`](tessera_core::splat::resolve) for why they count).
    pub fn resolve(&self, width: u32, height: u32, samples: &[u64]) -> Vec<[f32; 3]> {
        resolve(self.reach, width, height, &self.sums, samples)
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

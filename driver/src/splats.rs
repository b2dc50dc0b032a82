//! The film's splatted sums (see `core/src/splat.rs`): for each pixel, one running sum per pixel
//! its samples reach, kept beside its own [`PixelAccum`](tessera_core::film::PixelAccum) and carried with it through tiles,
//! passes, checkpoints and part files, so that every one is added to in sample-index order by
//! the one worker that renders its pixel.
use tessera_core::splat::{density_scale, resolve_rows, stride};

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
    /// [`resolve`](tessera_core::splat::resolve) for why they count): that function's bits,
    /// bands of rows made on the machine's cores where the image is large (each pixel reads
    /// `(2 reach + 1)^2` sources; at 512x512 one thread took about 60 ms of a render's end).
    pub fn resolve(&self, width: u32, height: u32, samples: &[u64]) -> Vec<[f32; 3]> {
        let pixels = width as usize * height as usize;
        assert_eq!(samples.len(), pixels, "resolve: one count per pixel");
        let scale = density_scale(samples);
        let mut out = vec![[0.0; 3]; pixels];
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        // Bands of at least 64k pixels: below that a thread costs more than it saves.
        let bands = cores.min(pixels / 65_536).max(1);
        let rows = (height as usize).div_ceil(bands);
        let band = |first: usize, out: &mut [[f32; 3]]| {
            let s = scale.as_deref();
            resolve_rows(self.reach, width, height, &self.sums, s, first as u32, out);
        };
        if bands == 1 {
            band(0, &mut out);
            return out;
        }
        std::thread::scope(|scope| {
            for (i, chunk) in out.chunks_mut(rows * width as usize).enumerate() {
                scope.spawn(move || band(i * rows, chunk));
            }
        });
        out
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

#[cfg(test)]
mod tests {
    use super::*;
    use tessera_core::splat::resolve;

    /// Random sums, equal and unequal counts: the bands give the one-thread function's bits;
    /// control: a band told the wrong first row does not.
    #[test]
    fn bands_of_rows_give_the_whole_image_bits() {
        let (w, h, reach) = (300u32, 451u32, 2u32);
        let mut s = Splats::new(reach, (w * h) as usize);
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for v in s.sums.iter_mut() {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            *v = (x >> 40) as f32 / (1u64 << 24) as f32;
        }
        let even = vec![3u64; (w * h) as usize];
        let uneven: Vec<u64> = (0..(w * h) as u64).map(|i| 1 + i % 5).collect();
        let bits =
            |img: &[[f32; 3]]| -> Vec<u32> { img.iter().flatten().map(|v| v.to_bits()).collect() };
        for counts in [&even, &uneven] {
            let one = resolve(reach, w, h, &s.sums, counts);
            assert_eq!(bits(&s.resolve(w, h, counts)), bits(&one));
            let scale = density_scale(counts);
            let rows = 200 * w as usize..210 * w as usize;
            let mut band = vec![[0.0f32; 3]; 10 * w as usize];
            resolve_rows(reach, w, h, &s.sums, scale.as_deref(), 200, &mut band);
            assert_eq!(bits(&band), bits(&one[rows.clone()]));
            resolve_rows(reach, w, h, &s.sums, scale.as_deref(), 201, &mut band);
            assert_ne!(bits(&band), bits(&one[rows]));
        }
    }
}

//! The independent sampler: one PCG32 stream per pixel, one window of it per sample.
//!
//! Scene parameters (`<sampler type="independent">`): `sample_count` (integer, default 4; read by
//! the driver). The random stream of a sample is a pure function of
//! `(seed, pixel x, pixel y, sample index)`: the seed and pixel are hashed into a PCG32 state and
//! stream selector, and the generator is advanced by `sample index * 2^32`, so each sample owns a
//! window of 2^32 draws. Nothing depends on tiles, threads or time, and one sample can be
//! replayed alone.
use super::Sampler;
use rand_core::Rng;
use rand_pcg::Pcg32;

/// Draws a sample may use before it would run into the next sample's window.
pub(crate) const SAMPLE_WINDOW: u64 = 1 << 32;

/// SplitMix64's finalizer: a bijective 64-bit mixer.
#[inline]
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The 64-bit key of a pixel under a seed (distinct pixels give unrelated keys).
#[inline]
pub(crate) fn pixel_key(seed: u64, x: u32, y: u32) -> u64 {
    mix64(seed ^ mix64((((x as u64) << 32) | y as u64) ^ 0x9e37_79b9_7f4a_7c15))
}

/// Independent uniform samples from a PCG32 stream keyed by seed, pixel and sample index.
#[derive(Clone, Debug)]
pub struct IndependentSampler {
    rng: Pcg32,
}

impl IndependentSampler {
    /// The stream of sample `index` of pixel `(x, y)` under `seed`.
    pub fn new(seed: u64, x: u32, y: u32, index: u64) -> Self {
        let key = pixel_key(seed, x, y);
        let mut rng = Pcg32::new(key, mix64(key ^ 0xda94_2042_e4dd_58b5));
        rng.advance(index.wrapping_mul(SAMPLE_WINDOW));
        IndependentSampler { rng }
    }
}

impl Sampler for IndependentSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        // 24 high bits: exactly representable, strictly below 1.
        (self.rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

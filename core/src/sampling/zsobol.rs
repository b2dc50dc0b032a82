//! The `zsobol` sampler: Owen-scrambled Sobol points laid out over the image in Morton (Z) order,
//! in the spirit of pbrt-v4's `ZSobolSampler` (after Ahmed and Wonka, "Screen-space blue-noise
//! diffusion of Monte Carlo sampling error via hierarchical ordering of pixels", 2020).
//!
//! Scene parameters (`<sampler type="zsobol">`, a Tessera extension): `sample_count` (integer,
//! default 4), `seed` (integer, default 0); both read by the driver.
//!
//! How a value is made. Sample `s` of pixel `(x, y)` has the *Morton index*
//! `m = (morton(x, y) << K) | (s mod 2^K)`, with `K = log2_spp` (the sample count rounded up to a
//! power of two, at most 32): the pixel's samples are one aligned block of `2^K` indices, and
//! the pixels of any aligned `2^j x 2^j` square form a larger aligned block. Each request (one
//! *dimension* for `next_1d`, two for `next_2d`) then:
//! 1. permutes `m` by a nested (Owen) scramble of its bits seeded by a hash of
//!    (seed, dimension, epoch), so each dimension visits the sequence in a different order while
//!    aligned blocks stay aligned blocks ([`scramble_index`](super::owen::scramble_index): the pixel bits by one scramble per
//!    dimension, the sample bits by one seeded by the pixel too); the epoch is `s >> K`, so
//!    samples beyond `2^K` start fresh randomizations instead of running into the next pixel;
//! 2. takes Sobol dimension 0 (and 1 for a 2D request) of the permuted index's low 32 bits
//!    ([`sobol_dim0`](super::sobol::sobol_dim0), [`sobol_dim1`](super::sobol::sobol_dim1));
//! 3. Owen-scrambles each coordinate with a seed hashed from (seed, dimension, epoch, the
//!    permuted index's high 32 bits) ([`owen_scramble_u32`](super::owen::owen_scramble_u32)), and keeps its top 24 bits.
//!
//! Dimensions. `next_1d` reads the next dimension and `next_2d` the next two; the integrators
//! jump to each stage's first dimension by the fixed per-bounce layout
//! ([`dimension_of`](super::dimension_of)), so bounce `d` of every path reads the same
//! dimensions whatever an earlier bounce skipped.
//!
//! Paired draws. A 2D draw that the layout pairs with an earlier one ([`paired_dimension`]:
//! the point on the emitter at bounce 0 with the camera's offset, the point on the emitter at
//! bounce `d + 1` with the BSDF direction of bounce `d`) does not permute the index with its
//! own scramble: it takes Sobol dimensions 2 and 3
//! ([`sobol_dim23_reversed`]) of its partner's permuted
//! index, Owen-scrambled with its own seeds. A pixel's points of the couple are then one 4D
//! (3, m, 4)-net (Sobol dimensions 0 to 3) instead of two 2D nets joined at random, which
//! stratifies what the couple integrates together (the light over the pixel, the light found
//! through a bounce). The paired 2D points alone form a (2, m, 2)-net (t = 1 for most m).
//! Measured on the benchmark scenes (128x128, 6 seeds): relMSE against the reference 2-8%
//! lower on veach_mis and 1-3% lower on cbox at 64 and 256 spp. Pairing the BSDF direction of
//! bounce 0 with the camera instead helped veach_mis more (15-24%) but cost cbox 2-4%: the
//! first direction's own points lose their (0, m, 2) stratification.
//!
//! Properties. A value is a pure function of (seed, `K`, pixel, sample index, dimension): no
//! state is shared between samples or pixels, nothing is allocated. For every dimension and
//! every `k <= K`, the first `2^k` samples of a pixel are an aligned block of indices, so their
//! 2D points form a (0, k, 2)-net (one point in every elementary interval of area `2^-k`) and
//! their 1D values one point in each interval `[i / 2^k, (i + 1) / 2^k)`; each value on its own
//! is uniform, and different dimensions are independent (up to the hash's quality). Power-of-two
//! sample counts are best; any other count uses the first `spp` samples of the next power of two
//! (unbiased, less evenly spread). The values of sample `s` depend on `K`, so an image rendered
//! with `K` from 64 spp differs from the first 64 samples of one rendered with `K` from 1024 spp;
//! for a fixed `K`, rendering samples `0..a` then `a..b` equals rendering `0..b`.
use super::layout::paired_dimension;
use super::owen::{mix64, reversed_lk, SAMPLE_SEED_MUL};
use super::sobol::{sobol_dim1_reversed, sobol_dim23_reversed};
use super::Sampler;
use glam::Vec2;

/// Largest `log2_spp`: a pixel's block holds at most 2^32 samples before the epoch changes.
pub const MAX_LOG2_SPP: u32 = 32;

/// Dimensions whose draws the caches built on this sampler keep (the pixel parts of a pixel's
/// table, and the lanes of an eight-sample group): the camera's 2 and 8 bounces of 7 fit with
/// room; later dimensions are computed per draw, as [`ZSobolSampler`] does. Here, below both
/// caches, so that neither has to reach into the other for it.
pub const CACHED_DIMENSIONS: usize = 64;

/// Spreads the 32 bits of `v` to the even bits of a `u64`.
#[inline]
fn spread_bits(v: u32) -> u64 {
    let mut x = v as u64;
    x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
    x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    x = (x | (x << 1)) & 0x5555_5555_5555_5555;
    x
}

/// The Morton (Z-order) code of a pixel: `x` on the even bits, `y` on the odd bits. Only the
/// low 16 bits of each coordinate are kept (images are at most 65536 pixels wide).
#[inline]
pub(crate) fn morton2(x: u32, y: u32) -> u64 {
    spread_bits(x & 0xffff) | (spread_bits(y & 0xffff) << 1)
}

/// The `K` for a sample count: `ceil(log2(spp))`, at most [`MAX_LOG2_SPP`].
pub fn log2_spp_for(spp: u64) -> u32 {
    let k = 64 - spp.max(1).saturating_sub(1).leading_zeros();
    k.min(MAX_LOG2_SPP)
}

/// Converts a 32-bit fraction to an `f32` in `[0, 1)` (its top 24 bits: exact, below 1).
#[inline]
pub fn to_unit(v: u32) -> f32 {
    (v >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The sample bits a draw scrambles: `within` (sample index modulo `2^k`, `k <= 32`) as the top
/// `k` bits of a word, bit-reversed.
#[inline]
pub(crate) fn sample_reversed(within: u32, k: u32) -> u32 {
    within.checked_shl(32 - k).unwrap_or(0).reverse_bits()
}

/// One sample's view of the Morton-ordered, Owen-scrambled Sobol sequence.
#[derive(Clone, Debug)]
pub struct ZSobolSampler {
    /// The Morton index `(morton(x, y) << K) | (s mod 2^K)`.
    morton_index: u64,
    /// `K`.
    log2_spp: u32,
    /// The pixel part `morton(x, y)`, bit-reversed as a 32-bit word.
    pixel_reversed: u32,
    /// The sample part `s mod 2^K` as the top `K` bits of a word, bit-reversed.
    sample_reversed: u32,
    /// `morton(x, y)` times the sample-seed multiplier (see [`sample_seed`](super::owen::sample_seed)), once per sample.
    pixel_mul: u64,
    /// Hash of the seed and the epoch.
    key: u64,
    /// The epoch `s >> K`.
    epoch: u64,
    /// The next dimension.
    dimension: u32,
}

/// What a dimension's draw takes from the pixel alone (see [`ZSobolSampler::pixel_draw`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PixelDraw {
    /// The permuted pixel bits, reversed and shifted below the sample's `K` bits.
    pub pixel_part: u32,
    /// Seed of the nested scramble of the sample bits.
    pub sample_seed: u32,
    /// Owen-scrambling seed of the first coordinate.
    pub seed_x: u32,
    /// Owen-scrambling seed of the second coordinate.
    pub seed_y: u32,
}

/// The scrambled 32-bit index and the two coordinate seeds of one dimension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DimensionDraw {
    /// Low 32 bits of the permuted index (what the Sobol matrices see).
    pub index: u32,
    /// Owen-scrambling seed of the first coordinate.
    pub seed_x: u32,
    /// Owen-scrambling seed of the second coordinate.
    pub seed_y: u32,
}

impl ZSobolSampler {
    /// Sample `index` of pixel `(x, y)` under `seed`, with pixel blocks of `2^log2_spp` samples
    /// (`log2_spp` is clamped to [`MAX_LOG2_SPP`]; use [`log2_spp_for`]).
    #[inline]
    pub fn new(seed: u64, x: u32, y: u32, index: u64, log2_spp: u32) -> Self {
        let k = log2_spp.min(MAX_LOG2_SPP);
        let within = index & ((1u64 << k) - 1);
        let epoch = index >> k;
        let pixel = morton2(x, y);
        ZSobolSampler {
            morton_index: (pixel << k) | within,
            log2_spp: k,
            pixel_reversed: (pixel as u32).reverse_bits(),
            sample_reversed: sample_reversed(within as u32, k),
            pixel_mul: pixel.wrapping_mul(SAMPLE_SEED_MUL),
            key: mix64(seed ^ mix64(epoch ^ 0x6a09_e667_f3bc_c909)),
            epoch,
            dimension: 0,
        }
    }

    /// The sampler of sample `index` of the same pixel, seed and `K`, when it lies in this
    /// sample's epoch (the same block): equal to `ZSobolSampler::new` for it, with only the
    /// sample's own bits recomputed. `None` for a sample of another epoch.
    #[inline]
    pub(crate) fn sibling(&self, index: u64) -> Option<ZSobolSampler> {
        let k = self.log2_spp;
        if index >> k != self.epoch {
            return None;
        }
        let mask = (1u64 << k) - 1;
        let within = index & mask;
        Some(ZSobolSampler {
            morton_index: (self.morton_index & !mask) | within,
            sample_reversed: sample_reversed(within as u32, k),
            dimension: 0,
            ..self.clone()
        })
    }

    /// The Morton index (before any permutation).
    pub fn morton_index(&self) -> u64 {
        self.morton_index
    }

    /// The next dimension to be drawn.
    pub fn dimension(&self) -> u32 {
        self.dimension
    }

    /// Where dimension `dim` of this sample reads the sequence (a pure function; for tests).
    ///
    /// The permuted index is `owen::scramble_index(morton_index, K, h)` for the dimension's hash
    /// `h`; it is assembled here in bit-reversed form, which is what the scrambles compute, so
    /// that only one bit reversal is left: `R(index) = (R(pixel') >> K) | (R(sample') << (32 - K))`.
    #[inline]
    pub fn draw(&self, dim: u32) -> DimensionDraw {
        self.finish_draw(self.pixel_draw(dim))
    }

    /// The part of dimension `dim`'s draw that depends only on (seed, epoch, `K`, pixel): the
    /// same for every sample of the pixel's block, so a pixel's samples can share it
    /// (`ZSobolPixel`).
    #[inline]
    pub fn pixel_draw(&self, dim: u32) -> PixelDraw {
        self.pixel_draw_hashed(self.dimension_hash(dim))
    }

    /// The hash of dimension `dim` that [`pixel_draw`](Self::pixel_draw) starts from: a function
    /// of (seed, epoch, `dim`) alone, the same for every pixel ([`same_key`](Self::same_key)).
    #[inline]
    pub fn dimension_hash(&self, dim: u32) -> u64 {
        mix64(self.key ^ (dim as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15))
    }

    /// Whether `other` has the same seed and epoch, and so the same
    /// [`dimension_hash`](Self::dimension_hash) for every dimension.
    #[inline]
    pub fn same_key(&self, other: &ZSobolSampler) -> bool {
        self.key == other.key
    }

    /// [`pixel_draw`](Self::pixel_draw) from the dimension's hash `h`.
    #[inline]
    pub(crate) fn pixel_draw_hashed(&self, h: u64) -> PixelDraw {
        let k = self.log2_spp;
        let pixel_r = reversed_lk(self.pixel_reversed, h as u32);
        // The permuted index's bits above 32 (the top K bits of the pixel word), reversed: only
        // hashed, so any bijection of them will do.
        let top = if k == 0 { 0 } else { pixel_r << (32 - k) };
        let s = mix64(h ^ top as u64 ^ 0xbb67_ae85_84ca_a73b);
        PixelDraw {
            pixel_part: pixel_r.checked_shr(k).unwrap_or(0),
            // `sample_seed(h, morton_index >> K)` with the pixel's product hoisted out.
            sample_seed: mix64(h ^ self.pixel_mul) as u32,
            seed_x: s as u32,
            seed_y: (s >> 32) as u32,
        }
    }

    /// Completes a draw with this sample's own bits.
    #[inline(always)]
    pub fn finish_draw(&self, p: PixelDraw) -> DimensionDraw {
        let k = self.log2_spp;
        let index_r = if k == 0 {
            p.pixel_part
        } else {
            p.pixel_part | (reversed_lk(self.sample_reversed, p.sample_seed) << (32 - k))
        };
        DimensionDraw {
            index: index_r.reverse_bits(),
            seed_x: p.seed_x,
            seed_y: p.seed_y,
        }
    }

    /// Whether `other` is a sample of the same pixel block and epoch (so its
    /// [`pixel_draw`](Self::pixel_draw)s equal this one's).
    #[inline]
    pub(crate) fn same_block(&self, other: &ZSobolSampler) -> bool {
        self.key == other.key
            && self.log2_spp == other.log2_spp
            && self.pixel_reversed == other.pixel_reversed
            && self.pixel_mul == other.pixel_mul
    }

    /// The 1D value of dimension `dim`, as a 32-bit fraction: the Owen-scrambled van der Corput
    /// point, `R(LK(R(R(index))))`.
    #[inline]
    pub fn value_1d(&self, dim: u32) -> u32 {
        value_1d_of(self.draw(dim))
    }

    /// The 2D value starting at dimension `dim`, as 32-bit fractions.
    #[inline]
    pub fn value_2d(&self, dim: u32) -> (u32, u32) {
        value_2d_of(self.draw(dim))
    }
}

/// The 1D value of a draw (see [`ZSobolSampler::value_1d`]).
#[inline(always)]
pub fn value_1d_of(d: DimensionDraw) -> u32 {
    reversed_lk(d.index, d.seed_x).reverse_bits()
}

/// The 2D value of a draw (see [`ZSobolSampler::value_2d`]).
#[inline(always)]
pub fn value_2d_of(d: DimensionDraw) -> (u32, u32) {
    scramble_pair(d.index, sobol_dim1_reversed(d.index), d)
}

/// The 2D value of a paired draw (see the module header): Sobol dimensions 2 and 3 of the
/// partner's permuted index `index`, Owen-scrambled with this draw's own seeds.
#[inline(always)]
pub fn value_2d_paired_of(d: DimensionDraw, index: u32) -> (u32, u32) {
    let (x, y) = sobol_dim23_reversed(index);
    scramble_pair(x, y, d)
}

/// Owen-scrambles two bit-reversed Sobol coordinates with `d`'s seeds and un-reverses them.
#[inline(always)]
fn scramble_pair(x_reversed: u32, y_reversed: u32, d: DimensionDraw) -> (u32, u32) {
    let x_r = reversed_lk(x_reversed, d.seed_x);
    let y_r = reversed_lk(y_reversed, d.seed_y);
    // Both coordinates un-reversed by one 64-bit reversal (the high word lands low).
    let both = (((x_r as u64) << 32) | y_r as u64).reverse_bits();
    (both as u32, (both >> 32) as u32)
}

impl Sampler for ZSobolSampler {
    #[inline(always)]
    fn next_1d(&mut self) -> f32 {
        let v = self.value_1d(self.dimension);
        self.dimension = self.dimension.wrapping_add(1);
        to_unit(v)
    }

    /// One 2D point of the pixel's (0, m, 2)-net, or a (2, m, 2)-net for a paired
    /// dimension; uses two dimension numbers, as in pbrt-v4.
    #[inline(always)]
    fn next_2d(&mut self) -> Vec2 {
        let (a, b) = match paired_dimension(self.dimension) {
            Some(p) => value_2d_paired_of(self.draw(self.dimension), self.draw(p).index),
            None => self.value_2d(self.dimension),
        };
        self.dimension = self.dimension.wrapping_add(2);
        Vec2::new(to_unit(a), to_unit(b))
    }

    #[inline]
    fn skip_1d(&mut self) {
        self.dimension = self.dimension.wrapping_add(1);
    }

    #[inline]
    fn start_dimension(&mut self, dim: u32) {
        self.dimension = dim;
    }
}

#[cfg(test)]
mod tests {
    use super::super::owen::{mix64, owen_scramble_u32, scramble_index};
    use super::super::sobol::{sobol_dim0, sobol_dim1};
    use super::*;

    /// The reversed-domain assembly equals the plain definition.
    #[test]
    fn draw_matches_the_definition() {
        for t in 0..5000u64 {
            let r = mix64(t);
            let (seed, x, y) = (r & 7, (r >> 8) as u32 & 0xffff, (r >> 24) as u32 & 0xffff);
            let k = (r >> 40) as u32 % 34;
            let index = mix64(r) >> ((r >> 50) % 64);
            let s = ZSobolSampler::new(seed, x, y, index, k);
            let dim = (r >> 56) as u32;
            let h = mix64(s.key ^ (dim as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15));
            let kk = k.min(MAX_LOG2_SPP);
            let full = scramble_index(s.morton_index, kk, h);
            let d = s.draw(dim);
            assert_eq!(d.index, full as u32, "k {k}");
            let v = owen_scramble_u32(sobol_dim0(d.index), d.seed_x);
            let w = owen_scramble_u32(sobol_dim1(d.index), d.seed_y);
            assert_eq!(s.value_2d(dim), (v, w));
            assert_eq!(s.value_1d(dim), v);
        }
    }
}

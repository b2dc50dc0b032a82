//! The zsobol sampler with its per-pixel work shared by the pixel's samples.
//!
//! Most of a zsobol draw depends only on (seed, epoch, `K`, pixel, dimension): the dimension's
//! hash, the scramble of the pixel's Morton bits and the coordinates' Owen seeds
//! ([`ZSobolSampler::pixel_draw`]). A renderer that takes a pixel's samples one after another
//! keeps a [`ZSobolPixel`] for the pixel; its samplers ([`ZSobolPixel::sampler`]) compute each
//! dimension's pixel part once, on first use, and only the sample's own bits per draw. One cache
//! can serve pixel after pixel ([`ZSobolPixel::move_to`]): its table is reused without being
//! cleared, and the dimensions' hashes, which depend on the seed and epoch alone, are kept
//! from pixel to pixel. That matters when each pixel takes one sample at a time (the first
//! waves of a benchmark, adaptive passes), where the table's set-up and the hashes were about a
//! third of a pixel's sampler work. When the caller says which samples of the pixel it takes
//! next ([`ZSobolPixel::set_run`]), samples of a run draw eight at a time
//! ([`super::zsobol_lanes`]). Values are exactly those of [`ZSobolSampler`] (tested below and
//! there): caching changes no bit.
use super::layout::paired_dimension;
use super::zsobol::{
    to_unit, value_1d_of, value_2d_of, value_2d_paired_of, PixelDraw, ZSobolSampler,
    CACHED_DIMENSIONS, MAX_LOG2_SPP,
};
use super::zsobol_lanes::{Group, LANES, MIN_LOG2_SPP};
use super::Sampler;
use core::ops::Range;
use glam::Vec2;

/// One pixel's shared draws.
#[derive(Clone, Debug)]
pub struct ZSobolPixel {
    seed: u64,
    x: u32,
    y: u32,
    log2_spp: u32,
    /// A sample of the block the table belongs to (`None` before the first sampler).
    block: Option<ZSobolSampler>,
    table: [PixelDraw; CACHED_DIMENSIONS],
    /// Bit `d` set when `table[d]` holds dimension `d`'s pixel part.
    filled: u64,
    /// A sample whose seed and epoch the hashes belong to (`None` before the first sampler).
    hash_block: Option<ZSobolSampler>,
    /// [`ZSobolSampler::dimension_hash`] of each dimension, for `hash_block`'s seed and epoch.
    hashes: [u64; CACHED_DIMENSIONS],
    /// Bit `d` set when `hashes[d]` holds dimension `d`'s hash.
    hashed: u64,
    /// The samples the caller is about to take ([`ZSobolPixel::set_run`]; empty by default).
    run: Range<u64>,
    /// The eight-sample group being drawn ([`super::zsobol_lanes`]).
    group: Group,
}

/// A sample draws from its eight-sample group only when the run takes at least this many of
/// the group's samples; otherwise filling eight lanes would cost more than the draws it saves.
pub const MIN_GROUP_SAMPLES: u64 = 4;

impl ZSobolPixel {
    /// The cache for pixel `(x, y)` under `seed` with pixel blocks of `2^log2_spp` samples
    /// (the arguments of [`ZSobolSampler::new`] but the sample index).
    pub fn new(seed: u64, x: u32, y: u32, log2_spp: u32) -> Self {
        ZSobolPixel {
            seed,
            x,
            y,
            log2_spp,
            block: None,
            table: [PixelDraw::default(); CACHED_DIMENSIONS],
            filled: 0,
            hash_block: None,
            hashes: [0; CACHED_DIMENSIONS],
            hashed: 0,
            run: 0..0,
            group: Group::default(),
        }
    }

    /// Tells the cache that the samples `run` of the pixel are taken next, in order: samples in
    /// it then draw their values eight at a time (`zsobol_lanes`) where the run takes
    /// at least `MIN_GROUP_SAMPLES` of a group. The values stay exactly the same; this only
    /// decides how they are computed. [`ZSobolPixel::move_to`] forgets the run.
    #[inline]
    pub fn set_run(&mut self, run: Range<u64>) {
        self.run = run;
    }

    /// Serves pixel `(x, y)` under `seed` with blocks of `2^log2_spp` samples from now on, as
    /// [`ZSobolPixel::new`] would, keeping the storage (not cleared: entries are marked
    /// empty) and the dimensions' hashes where the seed and epoch stay the same.
    #[inline]
    pub fn move_to(&mut self, seed: u64, x: u32, y: u32, log2_spp: u32) {
        (self.seed, self.x, self.y, self.log2_spp) = (seed, x, y, log2_spp);
        self.block = None;
        self.filled = 0;
        self.run = 0..0;
        self.group.clear();
    }

    /// The sampler of sample `index` of the pixel: the values of
    /// `ZSobolSampler::new(seed, x, y, index, log2_spp)`. A sample of another epoch (index
    /// beyond the pixel's block) starts the table afresh.
    #[inline]
    pub fn sampler(&mut self, index: u64) -> CachedZSobol<'_> {
        // A sample of the current block shares all but its own bits with the block's sample
        // (and then the block's key, which the hashes already belong to).
        let s = match self.block.as_ref().and_then(|b| b.sibling(index)) {
            Some(s) => s,
            None => {
                let s = ZSobolSampler::new(self.seed, self.x, self.y, index, self.log2_spp);
                if !self.block.as_ref().is_some_and(|b| b.same_block(&s)) {
                    self.block = Some(s.clone());
                    self.filled = 0;
                    self.group.clear();
                }
                if !self.hash_block.as_ref().is_some_and(|b| b.same_key(&s)) {
                    self.hash_block = Some(s.clone());
                    self.hashed = 0;
                }
                s
            }
        };
        let lane = self.lane_of(index);
        CachedZSobol {
            sample: s,
            pixel: self,
            last_2d: NO_DRAW,
            lane,
        }
    }

    /// Sample `index`'s lane in its eight-sample group, selecting the group, when the run takes
    /// enough of the group (and the block holds whole groups); `None` to draw alone.
    #[inline]
    fn lane_of(&mut self, index: u64) -> Option<usize> {
        let k = self.log2_spp.min(MAX_LOG2_SPP);
        if k < MIN_LOG2_SPP || !self.run.contains(&index) {
            return None;
        }
        let base = index & !(LANES as u64 - 1);
        let taken = self.run.end.min(base + LANES as u64) - self.run.start.max(base);
        if taken < MIN_GROUP_SAMPLES {
            return None;
        }
        self.group.select(base, k);
        Some((index - base) as usize)
    }
}

/// A zsobol sample drawing its pixel parts from a [`ZSobolPixel`].
#[derive(Debug)]
pub struct CachedZSobol<'a> {
    sample: ZSobolSampler,
    pixel: &'a mut ZSobolPixel,
    /// The dimension and permuted index of this sample's last unpaired 2D draw: a paired draw
    /// whose partner it is reads the index from here instead of completing the partner's draw
    /// again (the camera's offset and each BSDF direction are drawn just before the emitter
    /// position they pair with).
    last_2d: (u32, u32),
    /// This sample's lane in the pixel's eight-sample group, when it draws from the group.
    lane: Option<usize>,
}

/// `last_2d` before any 2D draw: dimension `u32::MAX` is never a partner.
const NO_DRAW: (u32, u32) = (u32::MAX, 0);

impl CachedZSobol<'_> {
    /// This sample's lane in its eight-sample group, if it draws from one (for tests).
    #[cfg(test)]
    pub(super) fn lane(&self) -> Option<usize> {
        self.lane
    }

    #[inline(always)]
    fn pixel_draw(&mut self, dim: u32) -> PixelDraw {
        let d = dim as usize;
        if d >= CACHED_DIMENSIONS {
            return self.sample.pixel_draw(dim);
        }
        let bit = 1u64 << d;
        let px = &mut *self.pixel;
        if px.filled & bit == 0 {
            if px.hashed & bit == 0 {
                px.hashes[d] = self.sample.dimension_hash(dim);
                px.hashed |= bit;
            }
            px.table[d] = self.sample.pixel_draw_hashed(px.hashes[d]);
            px.filled |= bit;
        }
        px.table[d]
    }
}

impl Sampler for CachedZSobol<'_> {
    #[inline(always)]
    fn next_1d(&mut self) -> f32 {
        let dim = self.sample.dimension();
        if let Some(lane) = self.lane {
            let d = dim as usize;
            if d < CACHED_DIMENSIONS {
                if !self.pixel.group.has_1d(d) {
                    let p = self.pixel_draw(dim);
                    self.pixel.group.fill_1d(d, &p);
                }
                self.sample.start_dimension(dim.wrapping_add(1));
                return self.pixel.group.get_1d(d, lane);
            }
        }
        let p = self.pixel_draw(dim);
        let d = self.sample.finish_draw(p);
        self.sample.start_dimension(dim.wrapping_add(1));
        to_unit(value_1d_of(d))
    }

    #[inline(always)]
    fn next_2d(&mut self) -> Vec2 {
        let dim = self.sample.dimension();
        if let Some(lane) = self.lane {
            let d = dim as usize;
            // A paired dimension's partner is an earlier one, so cached too.
            if d < CACHED_DIMENSIONS {
                if !self.pixel.group.has_2d(d) {
                    let p = self.pixel_draw(dim);
                    match paired_dimension(dim) {
                        Some(partner) => {
                            let q = self.pixel_draw(partner);
                            self.pixel.group.fill_2d_paired(d, &p, partner as usize, &q);
                        }
                        None => self.pixel.group.fill_2d(d, &p),
                    }
                }
                self.sample.start_dimension(dim.wrapping_add(2));
                let (x, y) = self.pixel.group.get_2d(d, lane);
                return Vec2::new(x, y);
            }
        }
        let p = self.pixel_draw(dim);
        let d = self.sample.finish_draw(p);
        self.sample.start_dimension(dim.wrapping_add(2));
        let (a, b) = match paired_dimension(dim) {
            Some(partner) => {
                let index = if self.last_2d.0 == partner {
                    self.last_2d.1
                } else {
                    let q = self.pixel_draw(partner);
                    self.sample.finish_draw(q).index
                };
                value_2d_paired_of(d, index)
            }
            None => {
                self.last_2d = (dim, d.index);
                value_2d_of(d)
            }
        };
        Vec2::new(to_unit(a), to_unit(b))
    }

    #[inline]
    fn skip_1d(&mut self) {
        self.sample.skip_1d();
    }

    #[inline]
    fn start_dimension(&mut self, dim: u32) {
        self.sample.start_dimension(dim);
    }
}

#[cfg(test)]
mod tests {
    use super::super::owen::mix64;
    use super::*;

    /// Draws the next 1D (`one_d`) or 2D value from both samplers and requires the same bits.
    fn same_draw(a: &mut ZSobolSampler, b: &mut CachedZSobol<'_>, one_d: bool) {
        if one_d {
            assert_eq!(a.next_1d().to_bits(), b.next_1d().to_bits());
        } else {
            let (va, vb) = (a.next_2d(), b.next_2d());
            assert_eq!(
                (va.x.to_bits(), va.y.to_bits()),
                (vb.x.to_bits(), vb.y.to_bits())
            );
        }
    }

    /// Every draw equals the plain sampler's, across pixels' sample runs that cross epochs, skip
    /// dimensions, and go past the cached range.
    #[test]
    fn same_values_as_the_plain_sampler() {
        let mut draws = 0;
        for t in 0..300u64 {
            let r = mix64(t + 17);
            let (seed, x, y) = (r & 3, (r >> 8) as u32 & 0x3ff, (r >> 24) as u32 & 0x3ff);
            let k = (r >> 40) as u32 % 8;
            let mut px = ZSobolPixel::new(seed, x, y, k);
            // Indices run across the block's end into the next epoch and back.
            let start = (r >> 48) % 4;
            let mut indices: alloc::vec::Vec<u64> = (start..start + (3u64 << k) + 2).collect();
            indices.push(start);
            for &i in &indices {
                let mut a = ZSobolSampler::new(seed, x, y, i, k);
                let mut b = px.sampler(i);
                for step in 0..40u32 {
                    let h = mix64(r ^ i ^ u64::from(step)) as u32;
                    if (h >> 3) & 3 == 0 {
                        let dim = (h >> 8) % 90;
                        a.start_dimension(dim);
                        b.start_dimension(dim);
                    }
                    same_draw(&mut a, &mut b, h & 0x100 == 0);
                    draws += 1;
                }
            }
        }
        assert!(draws > 100_000, "{draws}");
    }

    /// One cache moved from pixel to pixel (and across seeds, epochs and `K`, as a worker's
    /// cache is) gives the plain sampler's values: stale table entries and hashes are never
    /// served. Control: a table left filled by `move_to` would serve the previous pixel's parts,
    /// which differ, so the comparison can fail.
    #[test]
    fn a_moved_cache_gives_the_plain_values() {
        let mut px = ZSobolPixel::new(0, 0, 0, 0);
        let mut draws = 0;
        for t in 0..2000u64 {
            let r = mix64(t ^ 0x5eed);
            // Few seeds and sizes, so consecutive pixels often share the hashes' key.
            let (seed, x, y) = (r & 1, (r >> 8) as u32 & 0x3f, (r >> 24) as u32 & 0x3f);
            let k = [0, 2, 4][((r >> 40) % 3) as usize];
            px.move_to(seed, x, y, k);
            // One to three samples, sometimes in a later epoch.
            let start = if (r >> 44) & 3 == 0 {
                1u64 << k
            } else {
                (r >> 46) % 2
            };
            for i in start..start + 1 + (r >> 50) % 3 {
                let mut a = ZSobolSampler::new(seed, x, y, i, k);
                let mut b = px.sampler(i);
                for step in 0..12u32 {
                    same_draw(&mut a, &mut b, step % 3 == 2);
                    draws += 1;
                }
            }
        }
        assert!(draws > 20_000, "{draws}");
        // The control.
        let mut stale = ZSobolPixel::new(1, 5, 9, 4);
        let _ = stale.sampler(0).next_2d();
        stale.x = 6;
        stale.block = None;
        let filled = stale.filled;
        let mut s = stale.sampler(1);
        s.pixel.filled = filled;
        assert_ne!(s.next_2d(), ZSobolSampler::new(1, 6, 9, 1, 4).next_2d());
    }

    /// Draws in a path's order (camera offset, then per bounce the emitter choice and position,
    /// the BSDF component and direction, the roulette), where each emitter position reads the
    /// index its partner's draw left behind, equal the plain sampler's; so do the same draws when
    /// the partner was skipped (a BSDF that ignores its direction) and the index is computed
    /// afresh. Control: the paired values differ from an unpaired draw at the same dimension,
    /// so reading a wrong index would show.
    #[test]
    fn paired_draws_reuse_their_partners_index() {
        use super::super::layout::{dimension_of, Stage};
        let mut paired = 0;
        for (seed, k) in [(0u64, 0u32), (1, 3), (2, 6), (5, 10)] {
            let mut px = ZSobolPixel::new(seed, 13, 7, k);
            for i in 0..(1u64 << k).min(16) + 2 {
                for skip_direction in [false, true] {
                    let mut a = ZSobolSampler::new(seed, 13, 7, i, k);
                    let mut b = px.sampler(i);
                    same_draw(&mut a, &mut b, false);
                    for depth in 0..8 {
                        for s in [&mut a as &mut dyn Sampler, &mut b] {
                            s.start_dimension(dimension_of(depth, Stage::Light));
                        }
                        same_draw(&mut a, &mut b, true);
                        let dim = a.dimension();
                        assert!(paired_dimension(dim).is_some());
                        let unpaired = a.value_2d(dim);
                        let want = a.next_2d();
                        assert_eq!(b.next_2d(), want);
                        assert_ne!(to_unit(unpaired.0), want.x);
                        paired += 1;
                        same_draw(&mut a, &mut b, true);
                        if skip_direction {
                            a.skip_1d();
                            a.skip_1d();
                            b.skip_1d();
                            b.skip_1d();
                        } else {
                            same_draw(&mut a, &mut b, false);
                        }
                        same_draw(&mut a, &mut b, true);
                    }
                }
            }
        }
        assert!(paired > 500, "{paired}");
    }

    /// `skip_1d` leaves both samplers where `next_1d` would: the draws after it are equal
    /// (control: skipping nothing gives other values, so the comparison can fail).
    #[test]
    fn skip_is_a_draw_without_its_value() {
        let mut px = ZSobolPixel::new(3, 7, 11, 4);
        for i in 0..16u64 {
            let mut drawn = ZSobolSampler::new(3, 7, 11, i, 4);
            let mut plain = drawn.clone();
            let mut cached = px.sampler(i);
            let _ = drawn.next_1d();
            plain.skip_1d();
            cached.skip_1d();
            let want = drawn.next_2d();
            assert_eq!(plain.next_2d(), want);
            assert_eq!(cached.next_2d(), want);
            let mut unskipped = ZSobolSampler::new(3, 7, 11, i, 4);
            assert_ne!(unskipped.next_2d(), want);
        }
    }

    /// A cache moved to another pixel restarts its table instead of serving the old pixel's
    /// parts, which would be wrong (control: they differ, so the test above can fail).
    #[test]
    fn another_pixel_restarts_the_table() {
        let mut px = ZSobolPixel::new(1, 5, 9, 4);
        let _ = px.sampler(0).next_2d();
        let stale = px.table[0];
        assert_ne!(stale, ZSobolSampler::new(1, 6, 9, 1, 4).pixel_draw(0));
        px.move_to(1, 6, 9, 4);
        let got = px.sampler(1).next_2d();
        assert_eq!(got, ZSobolSampler::new(1, 6, 9, 1, 4).next_2d());
    }
}

//! Eight consecutive samples of one pixel drawn together: the zsobol values of a dimension for
//! a *group* of samples `base..base + 8` (`base` a multiple of 8), computed in one pass over
//! eight lanes that the compiler turns into vector instructions (no `unsafe`, no intrinsics:
//! plain loops over `[u32; 8]` of integer operations).
//!
//! Why. A renderer takes a pixel's samples one after another, and each sample draws the same
//! dimensions (the fixed per-bounce layout, [`dimension_of`](super::dimension_of)). With
//! `ZSobolPixel` (which draws through this module) the part of a draw that depends on the pixel alone is
//! already shared; what is left per sample (a Laine-Karras scramble of the sample bits, two or
//! three more for the coordinates, a Sobol matrix and three bit reversals) is the same
//! arithmetic on different sample bits, which eight lanes do at once. The first sample of a
//! group to reach a dimension fills the eight lanes; the others read theirs.
//!
//! Values. Lane `l` holds exactly what [`ZSobolSampler::new`](super::ZSobolSampler::new) for
//! sample `base + l` draws: the lanes call the one-sample value functions, and the test below
//! compares them with the plain sampler. Groups need `K >= 3` (a pixel block of at least 8
//! samples), so a group never straddles two blocks or epochs.
use super::owen::reversed_lk;
use super::zsobol::{
    sample_reversed, to_unit, value_1d_of, value_2d_of, value_2d_paired_of, DimensionDraw,
    PixelDraw, CACHED_DIMENSIONS,
};

/// Samples in a group.
pub const LANES: usize = 8;

/// Smallest `K` (log2 of the pixel block) for which groups are used.
pub const MIN_LOG2_SPP: u32 = 3;

/// The sample bits of each lane, as [`ZSobolSampler`](super::ZSobolSampler) keeps them: sample
/// `base + l` modulo `2^k`, as the top `k` bits of a word, bit-reversed. Requires
/// `MIN_LOG2_SPP <= k <= 32`.
#[inline]
pub fn sample_bits(base: u64, k: u32) -> [u32; LANES] {
    debug_assert!((MIN_LOG2_SPP..=32).contains(&k));
    // The bits above `k` fall off the top of the shifted word.
    core::array::from_fn(|l| sample_reversed((base + l as u64) as u32, k))
}

/// The permuted sequence index of each lane for the dimension whose pixel part is `p`
/// ([`ZSobolSampler::finish_draw`](super::ZSobolSampler::finish_draw) lane by lane).
#[inline]
pub fn indices(p: &PixelDraw, bits: &[u32; LANES], k: u32) -> [u32; LANES] {
    let mut out = [0u32; LANES];
    for l in 0..LANES {
        out[l] = (p.pixel_part | (reversed_lk(bits[l], p.sample_seed) << (32 - k))).reverse_bits();
    }
    out
}

/// 1D values of the lanes from their indices ([`value_1d_of`] lane by lane).
#[inline]
pub(crate) fn values_1d(index: &[u32; LANES], seed_x: u32) -> [f32; LANES] {
    let mut out = [0.0f32; LANES];
    for l in 0..LANES {
        out[l] = to_unit(value_1d_of(draw(index[l], seed_x, 0)));
    }
    out
}

/// Unpaired 2D values of the lanes from their indices ([`value_2d_of`] lane by lane): Sobol
/// dimensions 0 and 1, Owen-scrambled.
#[inline]
pub(crate) fn values_2d(index: &[u32; LANES], p: &PixelDraw) -> ([f32; LANES], [f32; LANES]) {
    let (mut x, mut y) = ([0.0f32; LANES], [0.0f32; LANES]);
    for l in 0..LANES {
        let (a, b) = value_2d_of(draw(index[l], p.seed_x, p.seed_y));
        (x[l], y[l]) = (to_unit(a), to_unit(b));
    }
    (x, y)
}

/// Paired 2D values of the lanes from their partners' indices ([`value_2d_paired_of`] lane by
/// lane): Sobol dimensions 2 and 3 of the partner's index, Owen-scrambled with this dimension's
/// seeds.
#[inline]
pub(crate) fn values_2d_paired(
    partner: &[u32; LANES],
    p: &PixelDraw,
) -> ([f32; LANES], [f32; LANES]) {
    let (mut x, mut y) = ([0.0f32; LANES], [0.0f32; LANES]);
    for l in 0..LANES {
        // The paired value reads only the seeds of its own draw.
        let (a, b) = value_2d_paired_of(draw(0, p.seed_x, p.seed_y), partner[l]);
        (x[l], y[l]) = (to_unit(a), to_unit(b));
    }
    (x, y)
}

/// A draw of one lane.
#[inline(always)]
fn draw(index: u32, seed_x: u32, seed_y: u32) -> DimensionDraw {
    DimensionDraw {
        index,
        seed_x,
        seed_y,
    }
}

/// A group's draws, kept while the group's samples are taken: per dimension (below
/// [`CACHED_DIMENSIONS`]) the lanes' permuted indices, 1D values and 2D values, each filled on
/// first use.
#[derive(Clone, Debug)]
pub(crate) struct Group {
    /// Sample index of lane 0, or `u64::MAX` when the group holds nothing.
    base: u64,
    /// `K` of the pixel block the group belongs to.
    k: u32,
    /// [`sample_bits`] of the group.
    bits: [u32; LANES],
    /// Bit `d` set when `index[d]` (resp. `one[d]`, `two[d]`) holds dimension `d`'s lanes.
    have_index: u64,
    have_1d: u64,
    have_2d: u64,
    index: [[u32; LANES]; CACHED_DIMENSIONS],
    one: [[f32; LANES]; CACHED_DIMENSIONS],
    two: [[[f32; LANES]; 2]; CACHED_DIMENSIONS],
}

impl Default for Group {
    fn default() -> Self {
        Group {
            base: u64::MAX,
            k: 0,
            bits: [0; LANES],
            have_index: 0,
            have_1d: 0,
            have_2d: 0,
            index: [[0; LANES]; CACHED_DIMENSIONS],
            one: [[0.0; LANES]; CACHED_DIMENSIONS],
            two: [[[0.0; LANES]; 2]; CACHED_DIMENSIONS],
        }
    }
}

impl Group {
    /// Forgets the group (its pixel, seed, epoch or block size changed).
    #[inline]
    pub fn clear(&mut self) {
        self.base = u64::MAX;
    }

    /// Makes the group the one starting at sample `base` (a multiple of [`LANES`]) of a block
    /// of `2^k` samples (`k >= MIN_LOG2_SPP`), starting it afresh unless it already is. The
    /// caller clears the group whenever the pixel parts change.
    #[inline]
    pub fn select(&mut self, base: u64, k: u32) {
        if base != self.base || k != self.k {
            self.base = base;
            self.k = k;
            self.bits = sample_bits(base, k);
            self.have_index = 0;
            self.have_1d = 0;
            self.have_2d = 0;
        }
    }

    /// Dimension `d`'s lane indices (pixel part `p`), computed on first use.
    #[inline]
    fn index(&mut self, d: usize, p: &PixelDraw) -> [u32; LANES] {
        if self.have_index & (1 << d) == 0 {
            self.index[d] = indices(p, &self.bits, self.k);
            self.have_index |= 1 << d;
        }
        self.index[d]
    }

    /// Whether dimension `d`'s 1D values are there.
    #[inline(always)]
    pub(crate) fn has_1d(&self, d: usize) -> bool {
        self.have_1d & (1 << d) != 0
    }

    /// Whether dimension `d`'s 2D values are there.
    #[inline(always)]
    pub(crate) fn has_2d(&self, d: usize) -> bool {
        self.have_2d & (1 << d) != 0
    }

    /// Computes dimension `d`'s 1D values (pixel part `p`).
    #[inline]
    pub(crate) fn fill_1d(&mut self, d: usize, p: &PixelDraw) {
        let index = self.index(d, p);
        self.one[d] = values_1d(&index, p.seed_x);
        self.have_1d |= 1 << d;
    }

    /// Computes dimension `d`'s unpaired 2D values (pixel part `p`).
    #[inline]
    pub(crate) fn fill_2d(&mut self, d: usize, p: &PixelDraw) {
        let index = self.index(d, p);
        let (x, y) = values_2d(&index, p);
        self.two[d] = [x, y];
        self.have_2d |= 1 << d;
    }

    /// Computes dimension `d`'s paired 2D values (pixel part `p`) from the indices of its
    /// partner dimension `partner` (pixel part `q`).
    #[inline]
    pub(crate) fn fill_2d_paired(
        &mut self,
        d: usize,
        p: &PixelDraw,
        partner: usize,
        q: &PixelDraw,
    ) {
        let index = self.index(partner, q);
        let (x, y) = values_2d_paired(&index, p);
        self.two[d] = [x, y];
        self.have_2d |= 1 << d;
    }

    /// Lane `lane`'s 1D value of dimension `d` (filled).
    #[inline(always)]
    pub(crate) fn get_1d(&self, d: usize, lane: usize) -> f32 {
        self.one[d][lane]
    }

    /// Lane `lane`'s 2D value of dimension `d` (filled).
    #[inline(always)]
    pub(crate) fn get_2d(&self, d: usize, lane: usize) -> (f32, f32) {
        (self.two[d][0][lane], self.two[d][1][lane])
    }
}

#[cfg(test)]
mod tests {
    use super::super::layout::paired_dimension;
    use super::super::owen::mix64;
    use super::super::{Sampler, ZSobolPixel, ZSobolSampler};
    use super::*;
    use crate::sampling::zsobol_pixel::MIN_GROUP_SAMPLES;

    /// Samples taken in runs (as the renderer takes a pixel's samples) draw exactly the plain
    /// sampler's values, 1D and 2D, paired or not, from any dimension (cached or not), with
    /// skips, across groups, epochs, block sizes and pixels sharing one cache. Control: most
    /// samples of the runs do draw from a group (so the group path is what is compared), and
    /// those of short runs do not.
    #[test]
    fn runs_draw_the_plain_values() {
        let mut px = ZSobolPixel::new(0, 0, 0, 0);
        let (mut grouped, mut alone, mut paired) = (0, 0, 0);
        for t in 0..1500u64 {
            let r = mix64(t ^ 0x1a4e5);
            let (seed, x, y) = (r & 1, (r >> 8) as u32 & 0x3f, (r >> 24) as u32 & 0x3f);
            let k = [0, 2, 3, 4, 6, 10][((r >> 40) % 6) as usize];
            px.move_to(seed, x, y, k);
            // A run of 1 to 40 samples from a random start, sometimes beyond the first epoch.
            let start = (r >> 46) % 24 + if (r >> 52) & 3 == 0 { 1 << k } else { 0 };
            let run = start..start + 1 + (r >> 55) % 40;
            px.set_run(run.clone());
            for i in run.clone() {
                let mut a = ZSobolSampler::new(seed, x, y, i, k);
                let mut b = px.sampler(i);
                let base = i & !7;
                let taken = run.end.min(base + 8) - run.start.max(base);
                if b.lane().is_some() {
                    grouped += 1;
                    assert!(k >= MIN_LOG2_SPP && taken >= MIN_GROUP_SAMPLES);
                } else {
                    alone += 1;
                    assert!(k < MIN_LOG2_SPP || taken < MIN_GROUP_SAMPLES);
                }
                for step in 0..24u32 {
                    let h = mix64(r ^ i ^ u64::from(step)) as u32;
                    if (h >> 3) & 3 == 0 {
                        // Any dimension, up to beyond the cached ones.
                        let dim = (h >> 8) % 80;
                        a.start_dimension(dim);
                        b.start_dimension(dim);
                    }
                    match (h >> 12) % 5 {
                        0 => assert_eq!(a.next_1d().to_bits(), b.next_1d().to_bits()),
                        1 => {
                            a.skip_1d();
                            b.skip_1d();
                        }
                        _ => {
                            paired += u32::from(paired_dimension(a.dimension()).is_some());
                            assert_eq!(a.next_2d(), b.next_2d(), "seed {seed} k {k} i {i}");
                        }
                    }
                }
            }
        }
        assert!(grouped > 10_000 && alone > 2_000, "{grouped} {alone}");
        assert!(paired > 1_000, "{paired}");
    }
}

//! Per-pixel accumulation of samples, in sample-index order, in f64.
use crate::Color;

/// The running sums of one pixel. Adding the same samples in the same order gives the same bits,
/// whichever thread does it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelAccum {
    /// Sum of accepted sample values.
    pub sum: [f64; 3],
    /// Sum of squared sample values (for variance estimates and statistical tests).
    pub sum_sq: [f64; 3],
    /// Number of accepted samples.
    pub count: u64,
    /// Number of samples dropped because they were not finite.
    pub dropped: u64,
    /// Rays the pixel's samples cast (camera, continuation and shadow rays; with path reuse,
    /// the rays of the pixel's group at each sample index it took): the cost that adaptive
    /// sampling weighs a pixel's noise against, a count so that it is the same on every
    /// machine. Only render loops that plan by it add to it (the driver's adaptive passes);
    /// [`PixelAccum::add`] does not.
    pub rays: u64,
}

impl PixelAccum {
    /// How many 64-bit words [`PixelAccum::to_words`] gives.
    pub const WORDS: usize = 9;
    /// Adds one sample; a non-finite one is counted and dropped.
    #[inline]
    pub fn add(&mut self, c: Color) {
        if !c.is_finite() {
            self.dropped += 1;
            return;
        }
        for k in 0..3 {
            let v = c[k] as f64;
            self.sum[k] += v;
            self.sum_sq[k] += v * v;
        }
        self.count += 1;
    }
    /// Merges sums of a later sample range (`other` must follow `self` in sample order).
    pub fn merge(&mut self, other: &PixelAccum) {
        for k in 0..3 {
            self.sum[k] += other.sum[k];
            self.sum_sq[k] += other.sum_sq[k];
        }
        self.count += other.count;
        self.dropped += other.dropped;
        self.rays += other.rays;
    }
    /// Every bit of the accumulator as [`PixelAccum::WORDS`] 64-bit words (sums and squares as
    /// `f64` bits, then `count`, `dropped`, `rays`), for files that must restore it exactly.
    pub fn to_words(&self) -> [u64; Self::WORDS] {
        [
            self.sum[0].to_bits(),
            self.sum[1].to_bits(),
            self.sum[2].to_bits(),
            self.sum_sq[0].to_bits(),
            self.sum_sq[1].to_bits(),
            self.sum_sq[2].to_bits(),
            self.count,
            self.dropped,
            self.rays,
        ]
    }
    /// The accumulator [`PixelAccum::to_words`] wrote.
    pub fn from_words(w: [u64; Self::WORDS]) -> PixelAccum {
        let f = f64::from_bits;
        PixelAccum {
            sum: [f(w[0]), f(w[1]), f(w[2])],
            sum_sq: [f(w[3]), f(w[4]), f(w[5])],
            count: w[6],
            dropped: w[7],
            rays: w[8],
        }
    }
    /// The pixel's estimate (mean of accepted samples; 0 if none).
    pub fn mean(&self) -> [f32; 3] {
        if self.count == 0 {
            return [0.0; 3];
        }
        let n = self.count as f64;
        [
            (self.sum[0] / n) as f32,
            (self.sum[1] / n) as f32,
            (self.sum[2] / n) as f32,
        ]
    }
}

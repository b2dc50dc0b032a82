//! A discrete distribution over `n` items by weight (e.g. triangles by area).
use alloc::vec::Vec;

/// Sampling of an index with probability proportional to its weight, by binary search in the
/// normalized cumulative sum; built once at scene-build time.
#[derive(Clone, Debug, Default)]
pub struct Discrete1D {
    cdf: Vec<f32>,
    total: f64,
}

impl Discrete1D {
    /// Builds from non-negative weights; `None` if the sum is not positive and finite.
    pub fn new(weights: impl IntoIterator<Item = f32>) -> Option<Self> {
        let mut sums = Vec::new();
        let mut acc = 0.0f64;
        for w in weights {
            if !(w >= 0.0) || !w.is_finite() {
                return None;
            }
            acc += w as f64;
            sums.push(acc);
        }
        if !(acc > 0.0) || !acc.is_finite() {
            return None;
        }
        let cdf = sums.iter().map(|s| (s / acc) as f32).collect();
        Some(Discrete1D { cdf, total: acc })
    }
    /// Number of items.
    pub fn len(&self) -> usize {
        self.cdf.len()
    }
    /// Whether there are no items.
    pub fn is_empty(&self) -> bool {
        self.cdf.is_empty()
    }
    /// Sum of the weights.
    pub fn total(&self) -> f64 {
        self.total
    }
    /// Probability of item `i`.
    pub fn pmf(&self, i: usize) -> f32 {
        let hi = self.cdf[i];
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        hi - lo
    }
    /// Picks an item for `u` in `[0,1)`; returns it and `u` rescaled to `[0,1)` within the item,
    /// so the same number can drive a second choice.
    pub fn sample_reuse(&self, u: f32) -> (usize, f32) {
        let n = self.cdf.len();
        let i = self.cdf.partition_point(|&c| c <= u).min(n - 1);
        // Skip zero-weight items that share a cdf value. (Written as a select, since `i == 0`
        // is as good as random for a two-triangle light; the compiler may still branch.)
        let lo = self.cdf[i.saturating_sub(1)];
        let lo = if i == 0 { 0.0 } else { lo };
        let p = self.cdf[i] - lo;
        let ur = if p > 0.0 {
            ((u - lo) / p).clamp(0.0, 1.0 - f32::EPSILON * 0.5)
        } else {
            0.0
        };
        (i, ur)
    }
}

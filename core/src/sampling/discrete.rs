//! A discrete distribution over `n` items by weight (e.g. triangles by area).
use alloc::vec::Vec;

/// Sampling of an index with probability proportional to its weight, by binary search in the
/// normalized cumulative sum; built once at scene-build time.
#[derive(Clone, Debug, Default)]
pub struct Discrete1D {
    /// `cdf[0] = 0`, then the normalized cumulative sums: item `i` covers
    /// `[cdf[i], cdf[i + 1])`. The leading zero spares a test of `i == 0` per lookup (a branch
    /// the compiler kept, mispredicted half the time for a two-triangle light).
    cdf: Vec<f32>,
    total: f64,
}

impl Discrete1D {
    /// Bytes of its table.
    pub fn memory_bytes(&self) -> usize {
        core::mem::size_of_val(&*self.cdf)
    }

    /// Builds from non-negative weights; `None` if the sum is not positive and finite.
    pub fn new(weights: impl IntoIterator<Item = f32>) -> Option<Self> {
        let mut sums = alloc::vec![0.0f64];
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
        self.cdf.len().saturating_sub(1)
    }
    /// Whether there are no items.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Sum of the weights.
    pub fn total(&self) -> f64 {
        self.total
    }
    /// Probability of item `i`.
    pub fn pmf(&self, i: usize) -> f32 {
        self.cdf[i + 1] - self.cdf[i]
    }
    /// Picks an item for `u` in `[0,1)`; returns it and `u` rescaled to `[0,1)` within the item,
    /// so the same number can drive a second choice.
    pub fn sample_reuse(&self, u: f32) -> (usize, f32) {
        let n = self.len();
        // The first item whose upper end is above `u` (zero-weight items, whose ends equal their
        // predecessors', are passed over).
        let i = self.cdf[1..].partition_point(|&c| c <= u).min(n - 1);
        let lo = self.cdf[i];
        let p = self.cdf[i + 1] - lo;
        let ur = if p > 0.0 {
            ((u - lo) / p).clamp(0.0, 1.0 - f32::EPSILON * 0.5)
        } else {
            0.0
        };
        (i, ur)
    }
}

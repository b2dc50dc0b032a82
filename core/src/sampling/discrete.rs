//! A discrete distribution over `n` items by weight (e.g. triangles by area).
//!
//! The lookup is a search of the cumulative sums. A binary search makes each load wait for the
//! one before, and with the tables of an environment map or a large mesh light out of the nearer
//! caches, that chain of misses was most of its time; [`count_at_most`] narrows the range by a
//! sixteenth per round instead, from fifteen loads that do not depend on each other, so the
//! misses of one round overlap. It finds the same index as the binary search for every `u`.
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
        let i = count_at_most(&self.cdf[1..], u).min(n - 1);
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

/// Probes per round of [`count_at_most`], plus one.
const WAYS: usize = 16;

/// The number of entries of the non-decreasing `sorted` that are `<= x` (what
/// `sorted.partition_point(|&c| c <= x)` returns), found in rounds of `WAYS - 1` independent
/// probes, each round keeping the one of `WAYS` slices the count falls in, then a count over the
/// last slice.
#[inline]
fn count_at_most(sorted: &[f32], x: f32) -> usize {
    // The count lies in `base..=base + size`.
    let (mut base, mut size) = (0usize, sorted.len());
    while size > WAYS {
        let step = size / WAYS;
        // Probes at the ends of the first `WAYS - 1` slices of `step` entries; those `<= x`
        // come first, so their number says which slice the count falls in.
        let mut m = 0;
        for t in 1..WAYS {
            m += usize::from(sorted[base + t * step - 1] <= x);
        }
        let last = m == WAYS - 1;
        base += m * step;
        size = if last { size - (WAYS - 1) * step } else { step };
    }
    base + sorted[base..base + size]
        .iter()
        .map(|&c| usize::from(c <= x))
        .sum::<usize>()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every length up to a few rounds, ties (zero weights) and values on the ends: the same
    /// count as the binary search.
    #[test]
    fn wide_search_counts_as_the_binary_search() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for n in (0..300).chain([511, 512, 513, 1024, 4097]) {
            let mut v: alloc::vec::Vec<f32> = (0..n)
                .map(|_| {
                    let r = next();
                    if r < 0.3 {
                        0.0
                    } else {
                        r
                    }
                })
                .collect();
            let mut acc = 0.0;
            for w in v.iter_mut() {
                acc += *w;
                *w = acc;
            }
            let mut xs: alloc::vec::Vec<f32> = (0..200).map(|_| next() * (acc + 1.0)).collect();
            xs.extend(v.iter().copied());
            xs.extend([-1.0, 0.0, f32::INFINITY]);
            for x in xs {
                assert_eq!(
                    count_at_most(&v, x),
                    v.partition_point(|&c| c <= x),
                    "n {n}, x {x}"
                );
            }
        }
    }
}

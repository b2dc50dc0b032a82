//! A discrete distribution over `n` items by weight (e.g. triangles by area).
//!
//! The lookup is a search of the cumulative sums. A binary search makes each load wait for the
//! one before, and with the tables of an environment map or a large mesh light out of the nearer
//! caches, that chain of misses was most of its time. Two things shorten the chain: a guide
//! table (for each of `n` equal steps of `u`, how many sums lie at or below the step's start)
//! narrows the search to the items whose sums fall within a few steps around `u`, and
//! [`count_at_most`] narrows what is left by a sixteenth per round, from fifteen loads that do not
//! depend on each other, so the misses of one round overlap. Both find the same index as the
//! binary search for every `u`.
use alloc::vec::Vec;

/// Sampling of an index with probability proportional to its weight, by binary search in the
/// normalized cumulative sum; built once at scene-build time.
#[derive(Clone, Debug, Default)]
pub struct Discrete1D {
    /// `cdf[0] = 0`, then the normalized cumulative sums: item `i` covers
    /// `[cdf[i], cdf[i + 1])`. The leading zero spares a test of `i == 0` per lookup (a branch
    /// the compiler kept, mispredicted half the time for a two-triangle light).
    cdf: Vec<f32>,
    /// `guide[k]`: how many of `cdf[1..]` are `<= k / n` for `n` items (`k` from 0 to `n`): the
    /// search for a `u` in step `k` starts at `guide[k - 1]` and ends at `guide[k + 2]` (a step
    /// of slack either side for the rounding of `u` times `n`). Empty past [`GUIDED_MAX`] items.
    guide: Vec<u32>,
    total: f64,
}

impl Discrete1D {
    /// Bytes of its tables.
    pub fn memory_bytes(&self) -> usize {
        core::mem::size_of_val(&*self.cdf) + core::mem::size_of_val(&*self.guide)
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
        let cdf: Vec<f32> = sums.iter().map(|s| (s / acc) as f32).collect();
        let steps = cdf.len() - 1;
        // Past 2^20 items, `u` times the count no longer places `u` within a step of its own in
        // f32; such tables are searched whole.
        let guide = match steps <= GUIDED_MAX {
            true => guide(&cdf[1..]),
            false => Vec::new(),
        };
        Some(Discrete1D {
            cdf,
            guide,
            total: acc,
        })
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
        let i = self.count_at_most(u).min(n - 1);
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

impl Discrete1D {
    /// How many of `cdf[1..]` are `<= u`: counted within the range the guide gives for `u`'s
    /// step (every sum below it is `<= u`, every one from its end on `> u`), or over all of them
    /// for a `u` outside `[0, 1)`.
    #[inline]
    fn count_at_most(&self, u: f32) -> usize {
        let sums = &self.cdf[1..];
        if self.guide.is_empty() || !(0.0..1.0).contains(&u) {
            return count_at_most(sums, u);
        }
        let steps = self.guide.len() - 1;
        let k = ((u * steps as f32) as usize).min(steps - 1);
        let lo = self.guide[k.saturating_sub(1)] as usize;
        let hi = self.guide[(k + 2).min(steps)] as usize;
        lo + count_at_most(&sums[lo..hi], u)
    }
}

/// The guide of the non-decreasing `sums` of `n` items: for each `k` from 0 to `n`, how many
/// sums are `<= k / n` (what [`count_at_most`] counts), in one sweep, as the thresholds rise.
fn guide(sums: &[f32]) -> Vec<u32> {
    let steps = sums.len();
    let mut below = 0;
    (0..=steps)
        .map(|k| {
            let t = k as f32 / steps as f32;
            below += sums[below..].iter().take_while(|&&c| c <= t).count();
            below as u32
        })
        .collect()
}

/// The most items a table keeps a guide for.
const GUIDED_MAX: usize = 1 << 20;

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

    /// The guided count is the full count (the binary search's) for uniform, peaked and
    /// zero-weight distributions of many sizes, at random `u`, at every step's start and its
    /// neighbouring floats, and at each sum and its neighbours. Control: without the step of
    /// slack below, some `u` just under a step's start is counted wrong.
    #[test]
    fn guided_count_is_the_full_count() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut control_caught = false;
        for n in [1usize, 2, 3, 7, 16, 17, 100, 513, 1024, 3000] {
            for shape in 0..3 {
                let w: alloc::vec::Vec<f32> = (0..n)
                    .map(|i| match shape {
                        0 => 1.0,
                        1 => {
                            let r = next();
                            if r < 0.4 {
                                0.0
                            } else {
                                r
                            }
                        }
                        _ => {
                            if i % 97 == 3 {
                                1e6
                            } else {
                                next() * 1e-3
                            }
                        }
                    })
                    .collect();
                let Some(d) = Discrete1D::new(w.iter().copied()) else {
                    continue;
                };
                let sums = &d.cdf[1..];
                let mut us: alloc::vec::Vec<f32> = (0..400).map(|_| next()).collect();
                for k in 0..=n {
                    let t = k as f32 / n as f32;
                    // The guide, built in one sweep, holds each step's full count.
                    assert_eq!(d.guide[k] as usize, sums.partition_point(|&c| c <= t));
                    us.extend([t, crate::math::next_down(t), crate::math::next_up(t)]);
                }
                for &c in sums {
                    us.extend([c, crate::math::next_down(c), crate::math::next_up(c)]);
                }
                us.extend([0.0, 1.0 - f32::EPSILON / 2.0, 1.0, -0.5, 2.0]);
                for u in us {
                    let want = sums.partition_point(|&c| c <= u);
                    assert_eq!(d.count_at_most(u), want, "n {n}, shape {shape}, u {u}");
                    if (0.0..1.0).contains(&u) {
                        let k = ((u * n as f32) as usize).min(n - 1);
                        let lo = d.guide[k] as usize;
                        let hi = d.guide[(k + 2).min(n)] as usize;
                        control_caught |= lo + count_at_most(&sums[lo..hi], u) != want;
                    }
                }
            }
        }
        assert!(control_caught, "control: no slack needed below any step");
    }

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

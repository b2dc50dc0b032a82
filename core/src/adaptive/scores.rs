//! The scores adaptive sampling shares a pass's samples by: each pixel's relative variance,
//! averaged over its 3x3 neighbourhood, weighed against what its samples cost (see the parent
//! module's notes).
use crate::film::PixelAccum;
use crate::math::sqrt_f64;
use alloc::vec;
use alloc::vec::Vec;

/// Each pixel's rays per sample attempted ([`PixelAccum::rays`]), a pixel that has none
/// (no sample yet, or no rays counted) taking the mean of those that have; `None` when no pixel
/// has any (accumulators from a loop that does not count rays).
pub(super) fn costs(pixels: &[PixelAccum]) -> Option<Vec<f64>> {
    let own = |p: &PixelAccum| {
        let n = p.count + p.dropped;
        (n > 0 && p.rays > 0).then(|| p.rays as f64 / n as f64)
    };
    let (sum, known) = pixels
        .iter()
        .filter_map(own)
        .fold((0.0f64, 0u64), |(s, k), c| (s + c, k + 1));
    if known == 0 {
        return None;
    }
    let mean = sum / known as f64;
    Some(pixels.iter().map(|p| own(p).unwrap_or(mean)).collect())
}

/// Scores weighing noise against cost: `sqrt(v / (c + fixed))` of the 3x3 means of the
/// relative variances `v` and the rays per sample `c` (the share that makes the most of a
/// fixed time, see the module notes).
pub(super) fn priced(v: &[f64], c: &[f64], fixed: f64, w: usize, h: usize) -> Vec<f64> {
    let (v, c) = (smooth(v, w, h), smooth(c, w, h));
    v.iter()
        .zip(&c)
        .map(|(&v, &c)| sqrt_f64(v / (c + fixed)))
        .collect()
}

/// The square root of each value's 3x3 mean ([`smooth`]).
pub(super) fn smooth_sqrt(v: &[f64], w: usize, h: usize) -> Vec<f64> {
    let mut score = smooth(v, w, h);
    for s in &mut score {
        *s = sqrt_f64(*s);
    }
    score
}

/// Each value's 3x3 mean (clipped at the borders), summed row by row in reading order from 0;
/// interior pixels take a straight-line sum in that same order.
fn smooth(v: &[f64], w: usize, h: usize) -> Vec<f64> {
    let mut score = vec![0.0f64; v.len()];
    for y in 0..h {
        let interior_row = y > 0 && y + 1 < h;
        for x in 0..w {
            let mean = if interior_row && x > 0 && x + 1 < w {
                let (a, b, c) = ((y - 1) * w + x, y * w + x, (y + 1) * w + x);
                let s = 0.0
                    + v[a - 1]
                    + v[a]
                    + v[a + 1]
                    + v[b - 1]
                    + v[b]
                    + v[b + 1]
                    + v[c - 1]
                    + v[c]
                    + v[c + 1];
                s / 9.0
            } else {
                let (mut s, mut k) = (0.0, 0.0);
                for yy in y.saturating_sub(1)..(y + 2).min(h) {
                    for xx in x.saturating_sub(1)..(x + 2).min(w) {
                        s += v[yy * w + xx];
                        k += 1.0;
                    }
                }
                s / k
            };
            score[y * w + x] = mean;
        }
    }
    score
}

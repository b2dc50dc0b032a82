//! Plans by blocks: with `AdaptiveParams::block` larger than one pixel, the pixels of
//! each aligned `width x height` block (clipped at the image's edge) are judged together and
//! take the same number of samples in a pass, so that an integrator sharing light among them
//! (path reuse, 4x2) finds all of them at each sample index.
use alloc::vec;
use alloc::vec::Vec;

/// The blocks of a `w x h` image, row by row: each block's pixel indices (row-major inside the
/// block), handed to `f` one block at a time.
fn for_each_block(w: usize, h: usize, b: (usize, usize), mut f: impl FnMut(&[usize])) {
    let (bw, bh) = (b.0.max(1), b.1.max(1));
    let mut members = Vec::with_capacity(bw * bh);
    for by in (0..h).step_by(bh) {
        for bx in (0..w).step_by(bw) {
            members.clear();
            for y in by..(by + bh).min(h) {
                members.extend((bx..(bx + bw).min(w)).map(|x| y * w + x));
            }
            f(&members);
        }
    }
}

/// Replaces each value by the mean of its block's values (summed in pixel order).
pub(super) fn block_mean(v: &mut [f64], w: usize, h: usize, b: (usize, usize)) {
    for_each_block(w, h, b, |m| {
        let mean = m.iter().map(|&i| v[i]).sum::<f64>() / m.len() as f64;
        for &i in m {
            v[i] = mean;
        }
    });
}

/// Integer counts from fractional ones (`want`, one per pixel, summing to about `budget`) that
/// are the same for every pixel of a block: a running sum over the blocks in order gives each
/// block the whole samples per pixel its running total reaches, carrying the rest to the next
/// block. What is left at the end (less than one block's size) goes, one sample per pixel, to
/// the pixels of the block that wanted most, so the counts sum to `budget` exactly; only that
/// block's pixels can differ, by one.
pub(super) fn round_blocks(
    want: &[f64],
    w: usize,
    h: usize,
    b: (usize, usize),
    budget: u64,
) -> Vec<u64> {
    let mut out = vec![0u64; want.len()];
    let (mut acc, mut given) = (0.0f64, 0u64);
    let mut biggest: Option<(f64, Vec<usize>)> = None;
    for_each_block(w, h, b, |m| {
        let total: f64 = m.iter().map(|&i| want[i]).sum();
        acc += total;
        let size = m.len() as u64;
        let reach = (libm::floor(acc) as u64).min(budget);
        let each = reach.saturating_sub(given) / size;
        for &i in m {
            out[i] = each;
        }
        given += each * size;
        let per_pixel = total / size as f64;
        if biggest.as_ref().is_none_or(|(p, _)| per_pixel > *p) {
            biggest = Some((per_pixel, m.to_vec()));
        }
    });
    if let Some((_, m)) = biggest {
        for &i in m.iter().cycle().take(budget.saturating_sub(given) as usize) {
            out[i] += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_equal_within_blocks_and_sum_to_the_budget() {
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            rng
        };
        for _ in 0..300 {
            let (w, h) = (1 + (next() % 9) as usize, 1 + (next() % 7) as usize);
            let b = (1 + (next() % 4) as usize, 1 + (next() % 3) as usize);
            let budget = next() % 200;
            let raw: Vec<f64> = (0..w * h).map(|_| (next() % 1000) as f64).collect();
            let sum: f64 = raw.iter().sum();
            let want: Vec<f64> = raw
                .iter()
                .map(|r| {
                    if sum > 0.0 {
                        r * budget as f64 / sum
                    } else {
                        0.0
                    }
                })
                .collect();
            let got = round_blocks(&want, w, h, b, budget);
            if sum > 0.0 {
                assert_eq!(got.iter().sum::<u64>(), budget, "{w}x{h} b {b:?}");
            }
            let mut uneven = 0;
            for_each_block(w, h, b, |m| {
                let (lo, hi) = m
                    .iter()
                    .fold((u64::MAX, 0), |(l, h), &i| (l.min(got[i]), h.max(got[i])));
                assert!(hi - lo <= 1, "{w}x{h} b {b:?}: {lo}..{hi}");
                uneven += usize::from(hi > lo);
                // Each block gets what it wanted per pixel, give or take the rest carried in
                // from the block before and the one handed out at the end (each less than one
                // block of samples), and one for the rounding.
                let want_b: f64 = m.iter().map(|&i| want[i]).sum::<f64>() / m.len() as f64;
                let slack = 2.0 * (b.0 * b.1) as f64 / m.len() as f64 + 1.0;
                assert!((lo as f64 - want_b).abs() <= slack, "{lo} for {want_b}");
            });
            assert!(uneven <= 1, "{uneven} uneven blocks");
        }
    }

    #[test]
    fn block_mean_averages_each_clipped_block() {
        // 3x3 image, blocks of 2: {0,1,3,4}, {2,5}, {6,7}, {8}.
        let mut v: Vec<f64> = (0..9).map(|i| i as f64).collect();
        block_mean(&mut v, 3, 3, (2, 2));
        assert_eq!(v, [2.0, 2.0, 3.5, 2.0, 2.0, 3.5, 6.5, 6.5, 8.0]);
        // Blocks of 1 change nothing.
        let mut u: Vec<f64> = (0..9).map(|i| i as f64 * 0.5).collect();
        let before = u.clone();
        block_mean(&mut u, 3, 3, (1, 1));
        assert_eq!(u, before);
        // 5x3 image, blocks 4 wide and 2 high: {0-3, 5-8}, {4, 9}, {10-13}, {14}.
        let mut r: Vec<f64> = (0..15).map(|i| i as f64).collect();
        block_mean(&mut r, 5, 3, (4, 2));
        let top = (1 + 2 + 3 + 5 + 6 + 7 + 8) as f64 / 8.0;
        let want = [
            top, top, top, top, 6.5, top, top, top, top, 6.5, 11.5, 11.5, 11.5, 11.5, 14.0,
        ];
        assert_eq!(r, want);
    }
}

//! Adaptive sampling: how many more samples each pixel takes in the next pass, decided from the
//! samples the pixels already hold.
//!
//! Model. A pixel whose samples have the per-sample *relative variance* `v` (each channel's sample
//! variance over `mean^2 + floor`, averaged over the three channels) has a relative squared error
//! of about `v / n` after `n` samples. For a fixed total number of samples, the sum over pixels
//! of `v_i / n_i` is least when `n_i` is proportional to `sqrt(v_i)`. (Giving every pixel the same
//! error instead, `n_i` proportional to `v_i`, gives exactly the mean error of uniform sampling.)
//! `floor` keeps dark pixels from claiming every sample; with the default 0.01 the measure is
//! the relative MSE that `tessera bench` reports.
//!
//! Samples do not cost the same: a pixel seeing glass traces long paths, one seeing the sky a
//! single ray. For a fixed *time*, with `c_i` the cost of a sample of pixel `i`, the sum is least
//! when `n_i` is proportional to `sqrt(v_i / c_i)`. The cost is counted, not timed, so that the
//! plan is the same on every machine: the rays a pixel's samples cast on average
//! ([`PixelAccum::rays`]) plus [`AdaptiveParams::sample_cost`] rays' worth of fixed work.
//!
//! A pass ([`plan_pass`]):
//! 1. estimates `v_i` of every pixel from its accumulator (the unbiased sample variance); a pixel
//!    holding one accepted sample, which has no variance of its own, from the spread of the
//!    values of the pixels around it ([`neighbourhood_variance`]), so that the first adaptive
//!    pass can follow a single warm-up sample per pixel; a pixel with no estimate counts as the
//!    noisiest pixel of the image;
//! 2. averages it, and the cost per sample, over the pixel's 3x3 neighbourhood: a few samples of
//!    one pixel can miss what its neighbours saw (a small bright light's edge), and the mean of
//!    nine estimates is far less noisy than one;
//! 3. sets every pixel's wanted total after the pass to `(1 - uniform)` of all samples shared in
//!    proportion to `sqrt(v_i / c_i)` plus `uniform` of them shared equally, so every pixel's count
//!    keeps growing with the total whatever its estimate says (the image converges everywhere);
//! 4. gives the pass's samples to the pixels below their wanted total, in proportion to what
//!    they lack, rounded by a running sum in pixel order so that the counts add up to the
//!    pass's budget exactly.
//!
//! With [`AdaptiveParams::block`] larger than one pixel, steps 3 and 4 go by aligned blocks:
//! a block's pixels share the mean of their scores and take one count each (`blocks.rs`).
//!
//! Everything is computed in `f64` in a fixed order from the accumulators alone: the same
//! accumulators give the same counts on any machine, whatever rendered them (thread count, tile
//! size). The counts depend on the samples themselves, so the image is not exactly unbiased: a
//! pixel whose first samples happened to be quiet gets fewer later samples. The uniform share,
//! the smoothing and the growing totals keep that effect small; see `docs/design/adaptive-and-reuse.md` for the measurements.
use crate::film::PixelAccum;

mod blocks;
mod params;
mod scores;
mod variance;
use alloc::vec::Vec;
pub use params::{AdaptiveParams, ZSOBOL_BLOCK_FACTOR};
use scores::{costs, priced, smooth_sqrt};
pub use variance::{neighbourhood_variance, relative_variance};

/// How many samples each pixel of a `width x height` image (row-major `pixels`) takes in the
/// next pass, `budget` in all (see the module notes). Pixels are counted by samples attempted
/// (`count + dropped`), as the renderer numbers them.
///
/// # Panics
/// If `pixels.len() != width * height`.
pub fn plan_pass(
    pixels: &[PixelAccum],
    width: u32,
    height: u32,
    budget: u64,
    params: &AdaptiveParams,
) -> Vec<u64> {
    let (w, h) = (width as usize, height as usize);
    assert_eq!(
        pixels.len(),
        w * h,
        "plan_pass: pixels do not match the size"
    );
    let n = pixels.len();
    if n == 0 {
        return Vec::new();
    }
    // Three buffers in all (the estimates, the scores, the counts), each written in one pass;
    // every sum runs in pixel order, as the module notes say.
    let raw: Vec<Option<f64>> = pixels
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if p.count == 1 {
                neighbourhood_variance(pixels, w, h, i, params.floor)
            } else {
                relative_variance(p, params.floor)
            }
        })
        .collect();
    let worst = raw.iter().flatten().fold(0.0f64, |m, &v| m.max(v));
    let mut v: Vec<f64> = raw.iter().map(|r| r.unwrap_or(worst)).collect();
    drop(raw);
    let mut score = match (params.sample_cost, costs(pixels)) {
        (Some(fixed), Some(c)) => priced(&v, &c, fixed, w, h),
        _ => smooth_sqrt(&v, w, h),
    };
    let block = (
        params.block.0.max(1) as usize,
        params.block.1.max(1) as usize,
    );
    let by_blocks = block != (1, 1);
    if by_blocks {
        blocks::block_mean(&mut score, w, h, block);
    }
    let total = pixels
        .iter()
        .map(|p| (p.count + p.dropped) as f64)
        .sum::<f64>()
        + budget as f64;
    let score_sum: f64 = score.iter().sum();
    let uniform = if score_sum > 0.0 && score_sum.is_finite() {
        params.uniform.clamp(0.0, 1.0)
    } else {
        1.0
    };
    let even = total * uniform / n as f64;
    // What each pixel lacks, in `v`'s storage (its estimates are no longer needed).
    let lack = &mut v;
    for ((l, &sc), p) in lack.iter_mut().zip(&score).zip(pixels) {
        let share = if uniform < 1.0 {
            total * (1.0 - uniform) * sc / score_sum
        } else {
            0.0
        };
        *l = (even + share - (p.count + p.dropped) as f64).max(0.0);
    }
    let lack_sum: f64 = lack.iter().sum();
    if lack_sum > 0.0 {
        for l in lack.iter_mut() {
            *l = budget as f64 * *l / lack_sum;
        }
    } else {
        lack.fill(budget as f64 / n as f64);
    }
    if by_blocks {
        return blocks::round_blocks(lack, w, h, block, budget);
    }
    round_to_budget(lack, budget)
}

/// [`plan_pass`] as the sample count each pixel should hold after the pass (what it holds,
/// `count + dropped`, plus its share), the form the renderer's per-pixel targets take.
pub fn pass_targets(
    pixels: &[PixelAccum],
    width: u32,
    height: u32,
    budget: u64,
    params: &AdaptiveParams,
) -> Vec<u64> {
    let mut targets = plan_pass(pixels, width, height, budget, params);
    for (t, p) in targets.iter_mut().zip(pixels) {
        *t += p.count + p.dropped;
    }
    targets
}

/// Integer counts from fractional ones by a running sum in index order (each count is the
/// growth of `floor(running sum)`), adding what rounding lost to the largest share, so that the
/// counts sum to `budget` exactly.
fn round_to_budget(want: &[f64], budget: u64) -> Vec<u64> {
    let mut out = Vec::with_capacity(want.len());
    let (mut acc, mut given) = (0.0f64, 0u64);
    for &x in want {
        acc += x;
        let upto = (libm::floor(acc) as u64).min(budget);
        out.push(upto.saturating_sub(given));
        given = given.max(upto);
    }
    if given < budget {
        let biggest = (0..want.len()).fold(0, |b, i| if want[i] > want[b] { i } else { b });
        if let Some(c) = out.get_mut(biggest) {
            *c += budget - given;
        }
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::math::sqrt_f64;
    use crate::Color;
    use alloc::vec;

    /// An accumulator of grey samples `values`.
    pub(crate) fn pixel(values: &[f32]) -> PixelAccum {
        let mut a = PixelAccum::default();
        for &v in values {
            a.add(Color::splat(v));
        }
        a
    }

    /// The plan as first written, kept to check that the leaner one computes the
    /// same counts.
    fn reference_plan(
        pixels: &[PixelAccum],
        w: usize,
        h: usize,
        budget: u64,
        params: &AdaptiveParams,
    ) -> Vec<u64> {
        let n = pixels.len();
        let raw: Vec<Option<f64>> = (0..n)
            .map(|i| match pixels[i].count {
                1 => neighbourhood_variance(pixels, w, h, i, params.floor),
                _ => relative_variance(&pixels[i], params.floor),
            })
            .collect();
        let worst = raw.iter().flatten().fold(0.0f64, |m, &v| m.max(v));
        let v: Vec<f64> = raw.iter().map(|r| r.unwrap_or(worst)).collect();
        let mut score = vec![0.0f64; n];
        for y in 0..h {
            for x in 0..w {
                let (mut s, mut k) = (0.0, 0.0);
                for yy in y.saturating_sub(1)..(y + 2).min(h) {
                    for xx in x.saturating_sub(1)..(x + 2).min(w) {
                        s += v[yy * w + xx];
                        k += 1.0;
                    }
                }
                score[y * w + x] = sqrt_f64(s / k);
            }
        }
        let have: Vec<f64> = pixels
            .iter()
            .map(|p| (p.count + p.dropped) as f64)
            .collect();
        let total = have.iter().sum::<f64>() + budget as f64;
        let score_sum: f64 = score.iter().sum();
        let uniform = if score_sum > 0.0 && score_sum.is_finite() {
            params.uniform.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let even = total * uniform / n as f64;
        let lack: Vec<f64> = (0..n)
            .map(|i| {
                let share = if uniform < 1.0 {
                    total * (1.0 - uniform) * score[i] / score_sum
                } else {
                    0.0
                };
                (even + share - have[i]).max(0.0)
            })
            .collect();
        let lack_sum: f64 = lack.iter().sum();
        let want: Vec<f64> = if lack_sum > 0.0 {
            lack.iter().map(|l| budget as f64 * l / lack_sum).collect()
        } else {
            vec![budget as f64 / n as f64; n]
        };
        round_to_budget(&want, budget)
    }

    /// The plan equals the reference on random images: sizes down to one pixel wide or high,
    /// pixels with no, one or many samples, dropped samples, dark and bright values, floors
    /// down to 0 (where a black pixel's estimate is 0 / 0) and uniform shares 0 to 1. It has
    /// power: adding the 3x3 neighbourhood in another order fails it (checked by hand).
    #[test]
    fn the_plan_equals_the_reference() {
        let mut rng = 0x1234_5678_9abc_def0u64;
        let mut next = move || {
            rng = crate::sampling::owen::mix64(rng.wrapping_add(0x9e37_79b9_7f4a_7c15));
            rng
        };
        let mut nonzero = 0;
        for t in 0..400 {
            let (w, h) = (1 + (next() % 23) as usize, 1 + (next() % 17) as usize);
            let bright = [0.0, 0.05, 1.0, 300.0][t % 4];
            let pixels: Vec<PixelAccum> = (0..w * h)
                .map(|_| {
                    let k = [0, 1, 2, 3, 8][(next() % 5) as usize];
                    let vals: Vec<f32> = (0..k)
                        .map(|_| (next() >> 40) as f32 / (1u64 << 24) as f32 * bright)
                        .collect();
                    let mut p = pixel(&vals);
                    p.dropped = next() % 3 / 2;
                    p
                })
                .collect();
            let params = AdaptiveParams {
                floor: [0.0, 1e-4, 0.01][t % 3],
                uniform: [0.0, 0.25, 1.0][(t / 3) % 3],
                warmup: 2,
                block: (1, 1),
                sample_cost: Some(1.0),
            };
            let budget = next() % 300;
            let got = plan_pass(&pixels, w as u32, h as u32, budget, &params);
            let want = reference_plan(&pixels, w, h, budget, &params);
            assert_eq!(got, want, "{w}x{h}, {params:?}, budget {budget}");
            nonzero += got.iter().filter(|&&c| c > 0).count();
            let targets = pass_targets(&pixels, w as u32, h as u32, budget, &params);
            for ((t, p), c) in targets.iter().zip(&pixels).zip(&got) {
                assert_eq!(*t, p.count + p.dropped + c);
            }
        }
        assert!(nonzero > 1000, "{nonzero}");
    }

    /// After one sample per pixel the first pass follows the image's edges: an image that is
    /// dark on the left and bright on the right gives the columns beside the edge more samples
    /// than the columns far from it, which get no more than the even share.
    #[test]
    fn the_first_pass_from_one_sample_follows_the_edges() {
        let (w, h) = (16usize, 8usize);
        let px: Vec<PixelAccum> = (0..w * h)
            .map(|i| pixel(&[if i % w < 8 { 0.0 } else { 10.0 }]))
            .collect();
        let budget = (w * h) as u64;
        let c = plan_pass(&px, w as u32, h as u32, budget, &AdaptiveParams::default());
        assert_eq!(c.iter().sum::<u64>(), budget);
        let column = |x: usize| (0..h).map(|y| c[y * w + x]).sum::<u64>();
        for x in [0, 1, 2, 3, 4, 5, 11, 12, 13, 14, 15] {
            assert!(column(x) <= h as u64, "column {x}: {}", column(x));
        }
        // The edge lies between columns 7 and 8; the dark side's relative variance is the
        // larger (the same spread over a smaller mean), and smoothing reaches one column further.
        for x in 6..9 {
            assert!(column(x) >= 4 * h as u64, "column {x}: {}", column(x));
        }
        assert!(column(9) > h as u64, "column 9: {}", column(9));
    }

    #[test]
    fn counts_add_up_to_the_budget() {
        for budget in [0u64, 1, 7, 100, 12_345] {
            let want: Vec<f64> = (0..37).map(|i| (i * i % 11) as f64 + 0.3).collect();
            let s: f64 = want.iter().sum();
            let want: Vec<f64> = want.iter().map(|w| w * budget as f64 / s).collect();
            let c = round_to_budget(&want, budget);
            assert_eq!(c.iter().sum::<u64>(), budget);
            for (c, w) in c.iter().zip(&want) {
                assert!((*c as f64 - w).abs() <= 2.0, "{c} vs {w}");
            }
        }
    }

    /// Noisy pixels get more samples, in proportion to sqrt of their (smoothed) relative
    /// variance; quiet ones still get the uniform share.
    #[test]
    fn noisy_pixels_get_more_samples() {
        // 8x8 image: left half constant (variance 0), right half samples 0 and 2.
        let (w, h) = (8u32, 8u32);
        let pixels: Vec<PixelAccum> = (0..64)
            .map(|i| {
                if i % 8 < 4 {
                    pixel(&[1.0, 1.0])
                } else {
                    pixel(&[0.0, 2.0])
                }
            })
            .collect();
        let p = AdaptiveParams::default();
        let budget = 64 * 6;
        let c = plan_pass(&pixels, w, h, budget, &p);
        assert_eq!(c.iter().sum::<u64>(), budget);
        let at = |x: usize, y: usize| c[y * 8 + x];
        // Far from the border between the halves, quiet pixels get only the uniform share:
        // total 64 * 8 samples, a quarter spread evenly = 2 per pixel, and they hold 2.
        assert_eq!(at(0, 3), 0);
        assert!(at(7, 3) > 8, "{c:?}");
        // The control: with a uniform share of 1 every pixel gets the same.
        let flat = plan_pass(&pixels, w, h, budget, &AdaptiveParams { uniform: 1.0, ..p });
        assert!(flat.iter().all(|&k| k == 6), "{flat:?}");
    }

    /// Pixels equally noisy share samples by what their samples cost: the left half's samples
    /// cast one ray each, the right half's nine, so with one ray's worth of fixed work a left
    /// sample costs a fifth of a right one and, away from the border, a left pixel takes about
    /// sqrt(5) times the samples. Controls: unpriced (`sample_cost: None`), and with no ray
    /// counted anywhere, the pixels share evenly, as with the unpriced plan.
    #[test]
    fn costly_pixels_get_fewer_samples() {
        let (w, h) = (8u32, 8u32);
        let mut pixels: Vec<PixelAccum> = (0..64).map(|_| pixel(&[0.0, 2.0])).collect();
        let uncounted = pixels.clone();
        for (i, p) in pixels.iter_mut().enumerate() {
            p.rays = if i % 8 < 4 { 2 } else { 18 };
        }
        let p = AdaptiveParams::default();
        let budget = 64 * 6;
        let c = plan_pass(&pixels, w, h, budget, &p);
        assert_eq!(c.iter().sum::<u64>(), budget);
        let ratio = c[3 * 8] as f64 / c[3 * 8 + 7] as f64;
        assert!((1.8..2.6).contains(&ratio), "{ratio}: {c:?}");
        let unpriced = AdaptiveParams {
            sample_cost: None,
            ..p
        };
        let flat = plan_pass(&pixels, w, h, budget, &unpriced);
        assert!(flat.iter().all(|&k| k == 6), "{flat:?}");
        assert_eq!(plan_pass(&uncounted, w, h, budget, &p), flat);
        // A cost below zero (outside the setting's range) gives scores that are not finite:
        // the samples are shared evenly, with no panic.
        let negative = AdaptiveParams {
            sample_cost: Some(-5.0),
            ..p
        };
        assert_eq!(plan_pass(&pixels, w, h, budget, &negative), flat);
    }

    /// A pixel with fewer than two samples counts as the noisiest, and an image with no noise at
    /// all is sampled evenly.
    #[test]
    fn unknown_and_flat_images() {
        let mut pixels = vec![pixel(&[1.0, 1.0]); 9];
        let c = plan_pass(&pixels, 3, 3, 90, &AdaptiveParams::default());
        assert!(c.iter().all(|&k| k == 10), "{c:?}");
        pixels[4] = pixel(&[1.0]);
        pixels[0] = pixel(&[0.0, 1.0]);
        let c = plan_pass(&pixels, 3, 3, 90, &AdaptiveParams::default());
        assert_eq!(c.iter().sum::<u64>(), 90);
        assert!(c[4] >= c[8], "{c:?}");
    }
}

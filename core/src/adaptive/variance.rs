//! Per-pixel noise estimates for adaptive sampling: the per-sample relative variance of a
//! pixel from its own samples, and, for a pixel holding a single sample, from its
//! neighbourhood's values (see the notes of the `adaptive` module).
use crate::film::PixelAccum;

/// The per-sample relative variance of one pixel (see the notes of the `adaptive` module), or
/// `None` with fewer than two accepted samples.
pub fn relative_variance(acc: &PixelAccum, floor: f64) -> Option<f64> {
    if acc.count < 2 {
        return None;
    }
    let n = acc.count as f64;
    let mut v = 0.0;
    for c in 0..3 {
        let mean = acc.sum[c] / n;
        let var = ((acc.sum_sq[c] - acc.sum[c] * mean) / (n - 1.0)).max(0.0);
        v += var / (mean * mean + floor);
    }
    Some(v / 3.0)
}

/// The per-sample relative variance of a pixel that holds one sample, estimated from its 3x3
/// neighbourhood: the pixels there that hold samples (itself included) taken as samples of one
/// distribution, their means' sample variance over `mean^2 + floor`, averaged over the
/// channels. `None` with fewer than two such pixels. Next to a bright edge this counts the
/// edge as noise, which it is at one sample per pixel: which side a pixel's sample falls on is
/// what its next samples average out.
pub fn neighbourhood_variance(
    pixels: &[PixelAccum],
    w: usize,
    h: usize,
    i: usize,
    floor: f64,
) -> Option<f64> {
    let (x, y) = (i % w, i / w);
    let (mut k, mut sum, mut sum_sq) = (0.0f64, [0.0f64; 3], [0.0f64; 3]);
    for yy in y.saturating_sub(1)..(y + 2).min(h) {
        for xx in x.saturating_sub(1)..(x + 2).min(w) {
            let p = &pixels[yy * w + xx];
            if p.count == 0 {
                continue;
            }
            let n = p.count as f64;
            for c in 0..3 {
                let m = p.sum[c] / n;
                sum[c] += m;
                sum_sq[c] += m * m;
            }
            k += 1.0;
        }
    }
    if k < 2.0 {
        return None;
    }
    let mut v = 0.0;
    for c in 0..3 {
        let mean = sum[c] / k;
        let var = ((sum_sq[c] - sum[c] * mean) / (k - 1.0)).max(0.0);
        v += var / (mean * mean + floor);
    }
    Some(v / 3.0)
}

#[cfg(test)]
mod tests {
    use super::super::tests::pixel;
    use super::*;
    use alloc::vec::Vec;

    /// A one-sample pixel's estimate is the spread of the values around it (its own and its
    /// neighbours' that hold samples, clipped at the image's border); fewer than two such values
    /// give none.
    #[test]
    fn neighbourhood_variance_of_known_values() {
        // 3x3: the centre and its left neighbour hold 2, the rest 0; one pixel holds nothing.
        let mut px: Vec<PixelAccum> = (0..9).map(|_| pixel(&[0.0])).collect();
        px[4] = pixel(&[2.0]);
        px[3] = pixel(&[2.0]);
        px[8] = PixelAccum::default();
        // Centre: values 2, 2 and six zeros: mean 0.5, unbiased variance (2 * 1.5^2 + 6 * 0.5^2) / 7.
        let v = neighbourhood_variance(&px, 3, 3, 4, 0.01).unwrap();
        let want = (2.0 * 2.25 + 6.0 * 0.25) / 7.0 / (0.25 + 0.01);
        assert!((v - want).abs() < 1e-12, "{v} {want}");
        // Top-left corner: its 2x2 block holds 0, 0, 2, 2: mean 1, variance 4 / 3.
        let v = neighbourhood_variance(&px, 3, 3, 0, 0.01).unwrap();
        assert!((v - 4.0 / 3.0 / 1.01).abs() < 1e-12, "{v}");
        // A pixel whose neighbours hold nothing.
        let lone: Vec<PixelAccum> = (0..4)
            .map(|i| {
                if i == 0 {
                    pixel(&[1.0])
                } else {
                    PixelAccum::default()
                }
            })
            .collect();
        assert_eq!(neighbourhood_variance(&lone, 2, 2, 0, 0.01), None);
        // Means, not single values, of neighbours that hold several samples.
        let mut px: Vec<PixelAccum> = (0..4).map(|_| pixel(&[1.0])).collect();
        px[3] = pixel(&[0.0, 2.0, 1.0]);
        assert_eq!(neighbourhood_variance(&px, 2, 2, 0, 0.01), Some(0.0));
    }

    #[test]
    fn relative_variance_of_known_samples() {
        // Samples 0 and 2: mean 1, unbiased variance 2, relative variance 2 / (1 + 0.01).
        let v = relative_variance(&pixel(&[0.0, 2.0]), 0.01).unwrap();
        assert!((v - 2.0 / 1.01).abs() < 1e-12, "{v}");
        assert_eq!(relative_variance(&pixel(&[3.0]), 0.01), None);
        assert_eq!(relative_variance(&pixel(&[0.5, 0.5, 0.5]), 0.01), Some(0.0));
    }
}

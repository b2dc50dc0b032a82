//! Splatting: a camera sample counts, weighted by the reconstruction filter, in every pixel the
//! filter reaches around it, and a pixel is its filter-weighted sum of sample values divided by
//! its summed weights, as Mitsuba 3's film develops it. Each sample serves several pixels, so at
//! equal samples the image's error is several times lower than when every pixel draws its own
//! filter-distributed samples (filter importance sampling, the other reconstruction, kept for
//! `--filter-sampling`).
//!
//! For the bits not to depend on threads, tiles, passes, resumes or splits, no sum is ever added
//! into by the samples of two pixels. Each pixel (a source) keeps one running sum for each pixel
//! its samples can reach (its targets, at offsets `-n..=n` on each axis), added in sample-index
//! order exactly like its own [`PixelAccum`](crate::film::PixelAccum); a target adds up its
//! sources' sums in a fixed order when the image is made ([`resolve`]). The price is
//! memory: `4 (2n + 1)^2` floats per pixel, 400 bytes for the default Gaussian (`n = 2`).
//!
//! Pixels may hold different numbers of samples (adaptive sampling): each source's sums then
//! count by its mean, so that the filter, not the sample density, weighs the neighbours.
use crate::camera::{Filter, FilterTable};
use crate::Color;
use alloc::vec::Vec;
use glam::{Vec2, Vec4};

/// The largest reach splatted: filters reaching further (a Lanczos filter of 5 lobes or more)
/// are applied by filter importance sampling instead.
pub const MAX_REACH: u32 = 4;

/// Offsets per axis at most: `2 MAX_REACH + 1`.
const MAX_SIDE: usize = 2 * MAX_REACH as usize + 1;

/// Floats kept per target: the weighted red, green and blue sums and the summed weight.
pub const CHANNELS: usize = 4;

/// Which pixels one sample reaches and with what weights: the filter's table and its reach `n`
/// (targets at offsets `-n..=n` from the sample's pixel on each axis, as Mitsuba 3's film border:
/// `n = ceil(radius - 1/2)`).
#[derive(Clone, Debug)]
pub struct Footprint {
    table: FilterTable,
    reach: u32,
}

impl Footprint {
    /// The footprint of `filter`, or `None` if its samples are not splatted: `box` (whose
    /// samples count in their own pixel only) and filters reaching further than [`MAX_REACH`].
    pub fn of(filter: &Filter) -> Option<Footprint> {
        let table = filter.table()?;
        let reach = libm::ceilf(table.radius - 0.5).max(0.0);
        if reach > MAX_REACH as f32 {
            return None;
        }
        Some(Footprint {
            table: table.clone(),
            reach: reach as u32,
        })
    }

    /// The reach `n`: targets lie at offsets `-n..=n` on each axis.
    pub fn reach(&self) -> u32 {
        self.reach
    }

    /// Floats kept per source pixel ([`stride`] of the reach).
    pub fn stride(&self) -> usize {
        stride(self.reach)
    }

    /// Adds a sample of value `c`, placed `offset` from its pixel's centre (each coordinate in
    /// `[-1/2, 1/2)`), to its pixel's sums `sums` ([`Footprint::stride`] floats): each target
    /// gets `c` times the filter's weight at the target's centre, and the weight. `c` must be
    /// finite (a non-finite sample is the caller's to drop).
    #[inline]
    pub fn add(&self, sums: &mut [f32], offset: Vec2, c: Color) {
        self.add_weighted(sums, &self.weights(offset), c);
    }

    /// The filter's weights, on each axis, for a sample placed `offset` from its pixel's
    /// centre: what [`Footprint::add_weighted`] takes, computed once for every value of the
    /// same sample (its colour, its square, its surface variables).
    #[inline]
    pub fn weights(&self, offset: Vec2) -> SplatWeights {
        // One loop per reach, so that each is unrolled with its sizes known.
        match self.reach {
            0 => self.weights_side::<1>(offset),
            1 => self.weights_side::<3>(offset),
            2 => self.weights_side::<5>(offset),
            3 => self.weights_side::<7>(offset),
            _ => self.weights_side::<MAX_SIDE>(offset),
        }
    }

    /// [`Footprint::weights`] for a footprint `SIDE` targets wide (`2 reach + 1`).
    #[inline(always)]
    fn weights_side<const SIDE: usize>(&self, offset: Vec2) -> SplatWeights {
        let n = (SIDE / 2) as f32;
        let mut w = SplatWeights {
            x: [0.0; MAX_SIDE],
            y: [0.0; MAX_SIDE],
        };
        for i in 0..SIDE {
            w.x[i] = self.table.eval(i as f32 - n - offset.x);
            w.y[i] = self.table.eval(i as f32 - n - offset.y);
        }
        w
    }

    /// [`Footprint::add`] with the sample's weights already found ([`Footprint::weights`] of
    /// this footprint): the same sums.
    #[inline]
    pub fn add_weighted(&self, sums: &mut [f32], w: &SplatWeights, c: Color) {
        match self.reach {
            0 => add_side::<1>(sums, w, c),
            1 => add_side::<3>(sums, w, c),
            2 => add_side::<5>(sums, w, c),
            3 => add_side::<7>(sums, w, c),
            _ => add_side::<MAX_SIDE>(sums, w, c),
        }
    }
}

/// One sample's filter weights on each axis, for the targets at offsets `-n..=n` (the first
/// `2n + 1` entries; see [`Footprint::weights`]).
#[derive(Clone, Copy, Debug)]
pub struct SplatWeights {
    x: [f32; MAX_SIDE],
    y: [f32; MAX_SIDE],
}

/// [`Footprint::add_weighted`] for a footprint `SIDE` targets wide (`2 reach + 1`).
#[inline(always)]
fn add_side<const SIDE: usize>(sums: &mut [f32], w: &SplatWeights, c: Color) {
    let sums = &mut sums[..CHANNELS * SIDE * SIDE];
    let (wx, wy) = (&w.x[..SIDE], &w.y[..SIDE]);
    // The value and a weight of 1 in four lanes: each lane's product and sum are the scalar
    // ones, so the bits are those of adding channel by channel. Every target is added to, those
    // of weight zero too: with `c` finite (the caller's guarantee) that adds a zero, which
    // leaves every sum's bits as they were (a sum starts at +0 and +0 + -0 is +0), and the
    // outer targets' zero weights depend on where the sample fell in its pixel, so testing for
    // them was a branch mispredicted about half the time.
    let c4 = Vec4::new(c.x, c.y, c.z, 1.0);
    for (row, &y) in sums.chunks_exact_mut(CHANNELS * SIDE).zip(wy) {
        for (t, &x) in row.chunks_exact_mut(CHANNELS).zip(wx) {
            let sum = Vec4::from_slice(t) + c4 * (x * y);
            sum.write_to_slice(t);
        }
    }
}

/// Floats kept per source pixel for a footprint of reach `n`: [`CHANNELS`] per target, targets
/// in row order from offset `(-n, -n)`.
pub fn stride(reach: u32) -> usize {
    let side = 2 * reach as usize + 1;
    CHANNELS * side * side
}

/// The image of a `width x height` buffer of sources' sums for a footprint of reach `reach`
/// (row-major, one [`stride`] per pixel): each pixel's weighted sum over the sources that reach
/// it, in a fixed order, divided by their summed weight (black where no weight reached it or
/// the quotient is not finite).
///
/// `samples` holds each source's samples attempted (row-major). Where the sources that hold
/// samples do not all hold the same number (adaptive sampling, a render stopped part-way
/// through a pass), each source's sums count divided by its number, so that every source
/// weighs as the filter says whatever its density: otherwise a pixel holding many samples
/// would pull its neighbours toward its own value, an error that more samples do not shrink.
/// Where they all hold the same number the division would cancel, and is not made (the bits
/// stay those of the plain sums).
///
/// # Panics
/// If `samples` does not hold one count per pixel.
pub fn resolve(
    reach: u32,
    width: u32,
    height: u32,
    sums: &[f32],
    samples: &[u64],
) -> Vec<[f32; 3]> {
    let pixels = width as usize * height as usize;
    assert_eq!(samples.len(), pixels, "resolve: one count per pixel");
    let scale = density_scale(samples);
    let mut out = alloc::vec![[0.0; 3]; pixels];
    resolve_rows(reach, width, height, sums, scale.as_deref(), 0, &mut out);
    out
}

/// The rows of [`resolve`]'s image from row `first` on, as many as `out` holds (whole rows),
/// `scale` being [`density_scale`] of the counts: each pixel is computed alone, so bands of
/// rows resolved apart (on several threads) give [`resolve`]'s bits.
pub fn resolve_rows(
    reach: u32,
    width: u32,
    height: u32,
    sums: &[f32],
    scale: Option<&[f64]>,
    first: u32,
    out: &mut [[f32; 3]],
) {
    let (w, h) = (width as i64, height as i64);
    let n = reach as i64;
    let side = 2 * n + 1;
    let stride = stride(reach);
    for (i, px) in out.iter_mut().enumerate() {
        let (tx, ty) = (i as i64 % w, first as i64 + i as i64 / w);
        let mut acc = [0.0f64; CHANNELS];
        // The source at offset `-d` from the target reaches it through its entry `d`; the
        // offsets whose source lies outside the image are skipped, the others taken in order.
        for dy in (-n).max(ty - h + 1)..=n.min(ty) {
            let sy = ty - dy;
            for dx in (-n).max(tx - w + 1)..=n.min(tx) {
                let entry = ((dy + n) * side + dx + n) as usize;
                let source = (sy * w + tx - dx) as usize;
                let at = source * stride + CHANNELS * entry;
                let v = &sums[at..at + CHANNELS];
                match scale {
                    // Times 1 where the counts are equal: the plain sums' bits, unmultiplied.
                    None => (0..CHANNELS).for_each(|k| acc[k] += v[k] as f64),
                    Some(s) => (0..CHANNELS).for_each(|k| acc[k] += v[k] as f64 * s[source]),
                }
            }
        }
        let weight = acc[3];
        *px = core::array::from_fn(|k| {
            let v = if weight != 0.0 { acc[k] / weight } else { 0.0 };
            if v.is_finite() {
                v as f32
            } else {
                0.0
            }
        });
    }
}

/// Each source's factor `1 / samples` when the sources that hold samples do not all hold the
/// same number (0 for a source holding none: its sums are zero), else `None`.
pub fn density_scale(samples: &[u64]) -> Option<Vec<f64>> {
    let mut held = samples.iter().copied().filter(|&k| k > 0);
    let first = held.next()?;
    if held.all(|k| k == first) {
        return None;
    }
    Some(
        samples
            .iter()
            .map(|&k| if k > 0 { 1.0 / k as f64 } else { 0.0 })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::GaussianFilter;

    fn gaussian() -> (Filter, Footprint) {
        let f = Filter::Gaussian(GaussianFilter::new(0.5));
        let fp = Footprint::of(&f).expect("the Gaussian splats");
        (f, fp)
    }

    /// Reaches as Mitsuba 3's film borders: `ceil(radius - 1/2)`; `box` does not splat.
    #[test]
    fn reach_follows_the_radius() {
        assert!(Footprint::of(&Filter::Box).is_none());
        assert_eq!(gaussian().1.reach(), 2);
        let tent = Filter::Tent(crate::camera::TentFilter::new(1.0));
        assert_eq!(Footprint::of(&tent).map(|f| f.reach()), Some(1));
        assert_eq!(stride(2), 100);
    }

    /// One sample's weight in each target is the filter's tabulated value at the distance from
    /// the sample to the target's centre, on each axis: written out here from the filter's
    /// definition (Mitsuba 3's table of 31 steps), not read from the footprint.
    #[test]
    fn one_sample_weighs_the_filter_at_each_target_centre() {
        let (_, fp) = gaussian();
        let mut sums = [0.0f32; 100];
        let offset = Vec2::new(0.3, -0.2);
        fp.add(&mut sums, offset, Color::new(2.0, 3.0, 5.0));
        let (r, alpha) = (2.0f32, -1.0f32 / (2.0 * 0.25));
        let table = |x: f32| {
            let i = (x.abs() * 31.0 / r) as usize;
            if i >= 31 {
                return 0.0;
            }
            let at = r * i as f32 / 31.0;
            (libm::expf(alpha * at * at) - libm::expf(alpha * r * r)).max(0.0)
        };
        for dy in -2i32..=2 {
            for dx in -2i32..=2 {
                let w = table(dx as f32 - offset.x) * table(dy as f32 - offset.y);
                let k = 4 * ((dy + 2) * 5 + dx + 2) as usize;
                assert_eq!(sums[k + 3], w, "weight at ({dx}, {dy})");
                assert_eq!(sums[k], 2.0 * w, "red at ({dx}, {dy})");
                assert_eq!(sums[k + 2], 5.0 * w, "blue at ({dx}, {dy})");
            }
        }
        // The sample lies right of and above its pixel's centre: two pixels left it reaches
        // nothing (distance 2.3 > radius), two pixels right it does (1.7).
        assert_eq!(sums[4 * (2 * 5) + 3], 0.0);
        assert!(sums[4 * (2 * 5 + 4) + 3] > 0.0);
    }

    /// Samples of one value, wherever they lie, give every pixel exactly that value (up to f32
    /// rounding of the sums), also at the image's edges and where few samples reach; the
    /// control, an image whose sources' sums are shifted by one pixel, is not what was splatted.
    #[test]
    fn a_constant_is_reproduced_everywhere_and_placement_matters() {
        let (_, fp) = gaussian();
        let (w, h) = (7u32, 5u32);
        let mut sums = alloc::vec![0.0f32; (w * h) as usize * fp.stride()];
        let mut u = 0.123f32;
        let mut next = || {
            u = (u * 997.0 + 0.371).fract();
            u - 0.5
        };
        let c = Color::new(0.25, 1.5, 4.0);
        for i in 0..(w * h) as usize {
            // Pixels take 1 to 3 samples.
            for _ in 0..1 + i % 3 {
                let o = Vec2::new(next(), next());
                fp.add(&mut sums[i * 100..(i + 1) * 100], o, c);
            }
        }
        let held: Vec<u64> = (0..(w * h) as u64).map(|i| 1 + i % 3).collect();
        for p in resolve(2, w, h, &sums, &held) {
            for k in 0..3 {
                assert!((p[k] - c[k]).abs() <= 4.0 * f32::EPSILON * c[k], "{p:?}");
            }
        }
        // A value in one pixel only: it spreads to its neighbours, and nowhere else.
        let mut one = alloc::vec![0.0f32; (w * h) as usize * 100];
        for i in 0..(w * h) as usize {
            let v = if i == 17 { c } else { Color::ZERO };
            fp.add(&mut one[i * 100..(i + 1) * 100], Vec2::ZERO, v);
        }
        let ones = alloc::vec![1u64; (w * h) as usize];
        let img = resolve(2, w, h, &one, &ones);
        assert!(img[17][0] > img[16][0] && img[16][0] > 0.0);
        // Two pixels away lies the Gaussian's radius, where its weight is zero.
        assert_eq!(img[17 - 2][0], 0.0);
        let mut shifted = one[100..].to_vec();
        shifted.extend_from_slice(&[0.0; 100]);
        assert_ne!(resolve(2, w, h, &shifted, &ones)[17], img[17]);
    }

    /// Sources of unequal density weigh as the filter says: a row of pixels of different
    /// values, each sample at its pixel's centre, gives the same image whether the pixels hold
    /// 1, 7, 1, 3 and 1 samples or one each (up to rounding); the control, the same sums
    /// resolved as if every source held one sample, is pulled toward the pixel holding 7.
    /// Equal counts resolve to the plain sums' bits, whatever the count.
    #[test]
    fn unequal_densities_weigh_as_the_filter_says() {
        let (_, fp) = gaussian();
        let (w, h) = (5u32, 1u32);
        let values = [1.0f32, 9.0, 2.0, 0.5, 4.0];
        let splat = |counts: &[u64]| {
            let mut sums = alloc::vec![0.0f32; 5 * fp.stride()];
            for (i, (&v, &k)) in values.iter().zip(counts).enumerate() {
                for _ in 0..k {
                    fp.add(
                        &mut sums[i * 100..(i + 1) * 100],
                        Vec2::ZERO,
                        Color::splat(v),
                    );
                }
            }
            sums
        };
        let ones = [1u64; 5];
        let even = resolve(2, w, h, &splat(&ones), &ones);
        let counts = [1u64, 7, 1, 3, 1];
        let uneven = splat(&counts);
        for (a, b) in resolve(2, w, h, &uneven, &counts).iter().zip(&even) {
            assert!(
                (a[0] - b[0]).abs() <= 8.0 * f32::EPSILON * b[0],
                "{a:?} {b:?}"
            );
        }
        let pulled = resolve(2, w, h, &uneven, &ones);
        assert!(
            pulled[2][0] > even[2][0] * 1.5,
            "{:?} {:?}",
            pulled[2],
            even[2]
        );
        let fours = [4u64; 5];
        let plain = resolve(2, w, h, &splat(&fours), &fours);
        let as_ones = resolve(2, w, h, &splat(&fours), &ones);
        assert_eq!(plain, as_ones);
        // A source without samples does not make the others unequal.
        assert_eq!(density_scale(&[0, 3, 3, 0]), None);
        assert!(density_scale(&[0, 3, 2, 0]).is_some());
    }
}

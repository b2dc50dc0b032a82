//! Pixel reconstruction filters, applied by filter importance sampling: each camera sample is
//! offset from its pixel's centre with density proportional to the filter and keeps unit weight,
//! so every sample lands in exactly one pixel (the tile that owns the pixel owns the sample).
//!
//! Scene parameters (`<rfilter>` in `<film>`): `box` (none; radius 0.5 pixel), `gaussian`
//! (`stddev`, float, default 0.5; radius 4 stddev, truncated, shifted to zero at the radius and
//! tabulated as in Mitsuba 3). The default filter is gaussian, as in Mitsuba 3 and Nori.
use alloc::vec::Vec;
use glam::Vec2;

/// Entries of the filter's tabulated profile over `[0, radius]`, as in Mitsuba 3.
const TABLE: usize = 31;

/// A truncated Gaussian, tabulated as Mitsuba 3 does (31 constant steps over `|x|` in
/// `[0, radius]`, each the filter's value at the step's start) and sampled exactly from that
/// step function, so the expected image equals Mitsuba's weighted splatting.
#[derive(Clone, Debug)]
pub struct GaussianFilter {
    /// Standard deviation in pixels.
    pub stddev: f32,
    /// Support radius in pixels.
    pub radius: f32,
    /// Cumulative weight of the steps, over `[-radius, radius]` (2 * TABLE steps), normalized.
    cdf: Vec<f32>,
}

impl GaussianFilter {
    /// The filter with the given standard deviation (radius = 4 stddev).
    pub fn new(stddev: f32) -> Self {
        let radius = 4.0 * stddev;
        let alpha = -1.0 / (2.0 * stddev * stddev);
        let bias = libm::expf(alpha * radius * radius);
        let step = |i: usize| {
            let x = radius * i as f32 / TABLE as f32;
            (libm::expf(alpha * x * x) - bias).max(0.0) as f64
        };
        // Steps from -radius to radius: mirror of the table, then the table.
        let weights = (0..TABLE).rev().chain(0..TABLE).map(step);
        let mut cdf = Vec::with_capacity(2 * TABLE + 1);
        cdf.push(0.0f32);
        let mut acc = 0.0f64;
        let sums: Vec<f64> = weights
            .map(|w| {
                acc += w;
                acc
            })
            .collect();
        cdf.extend(sums.iter().map(|s| (s / acc) as f32));
        GaussianFilter {
            stddev,
            radius,
            cdf,
        }
    }
    fn sample_1d(&self, u: f32) -> f32 {
        let n = 2 * TABLE;
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, n) - 1;
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let t = if c1 > c0 {
            ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        -self.radius + 2.0 * self.radius * (i as f32 + t) / n as f32
    }
}

/// A reconstruction filter.
#[derive(Clone, Debug)]
pub enum Filter {
    /// The pixel's own square.
    Box,
    /// Truncated Gaussian.
    Gaussian(GaussianFilter),
}

impl Filter {
    /// Offset of a sample from its pixel's centre, in pixels.
    #[inline]
    pub fn sample(&self, u: Vec2) -> Vec2 {
        match self {
            Filter::Box => u - Vec2::splat(0.5),
            Filter::Gaussian(g) => Vec2::new(g.sample_1d(u.x), g.sample_1d(u.y)),
        }
    }
}

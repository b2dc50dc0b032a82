//! A filter profile tabulated as Mitsuba 3 tabulates every reconstruction filter: 31 constant
//! steps over `|x|` in `[0, radius]`, each the filter's value at the step's start, mirrored to
//! `[-radius, radius]`. Mitsuba 3 splats samples with these step weights; Tessera samples camera
//! offsets exactly from the same step function, so both expect the same image.
use alloc::vec::Vec;

/// Steps of the profile over `[0, radius]`, as in Mitsuba 3.
pub const STEPS: usize = 31;

/// The normalized step function of a filter over `[-radius, radius]`, ready to sample.
#[derive(Clone, Debug)]
pub struct StepProfile {
    /// Support radius in pixels.
    pub radius: f32,
    /// Cumulative weight of the steps over `[-radius, radius]` (2 * STEPS steps), normalized.
    cdf: Vec<f32>,
}

impl StepProfile {
    /// The profile of a filter of support `radius` whose value at the start of step `i` (at
    /// `x = radius * i / STEPS`) is `value(i)`; values must be non-negative, not all zero.
    pub fn new(radius: f32, value: impl Fn(usize) -> f64) -> Self {
        // Steps from -radius to radius: mirror of the table, then the table.
        let weights = (0..STEPS).rev().chain(0..STEPS).map(value);
        let mut cdf = Vec::with_capacity(2 * STEPS + 1);
        cdf.push(0.0f32);
        let mut acc = 0.0f64;
        let sums: Vec<f64> = weights
            .map(|w| {
                acc += w;
                acc
            })
            .collect();
        cdf.extend(sums.iter().map(|s| (s / acc) as f32));
        StepProfile { radius, cdf }
    }

    /// An offset in `[-radius, radius]` with density proportional to the steps, from `u`.
    pub fn sample(&self, u: f32) -> f32 {
        self.sample_step(u).1
    }

    /// [`StepProfile::sample`], with the index of the step the offset lies in (0 for the step
    /// starting at `-radius`, `2 * STEPS - 1` for the last).
    pub(crate) fn sample_step(&self, u: f32) -> (usize, f32) {
        let n = 2 * STEPS;
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, n) - 1;
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let t = if c1 > c0 {
            ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        (
            i,
            -self.radius + 2.0 * self.radius * (i as f32 + t) / n as f32,
        )
    }
}

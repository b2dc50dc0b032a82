//! A filter profile with negative lobes (Mitchell-Netravali, Catmull-Rom, Lanczos), tabulated as
//! Mitsuba 3 tabulates every filter ([`StepProfile`]'s steps), and sampled for filter importance
//! sampling without bias: offsets are drawn with density proportional to `|f|`, and each carries
//! the weight `sign(f) * ∫|f| / ∫f`, whose expectation under that density is 1 on every
//! function of the offset weighted by `f / ∫f` — the image Mitsuba 3 gets by splatting with `f`
//! and dividing by the splatted weights.
use super::step_profile::{StepProfile, STEPS};
use alloc::vec::Vec;

/// The step function of a signed filter over `[-radius, radius]`, ready to sample.
#[derive(Clone, Debug)]
pub struct SignedProfile {
    /// The steps' absolute values, sampled.
    magnitude: StepProfile,
    /// Whether each step (of `2 * STEPS`, from `-radius`) is negative.
    negative: Vec<bool>,
    /// `∫|f| / ∫f` over `[-radius, radius]`.
    ratio: f32,
}

impl SignedProfile {
    /// The profile of a filter of support `radius` whose value at the start of step `i` (at
    /// `x = radius * i / STEPS`) is `value(i)`; `None` unless the steps' integral is positive
    /// and finite.
    pub fn new(radius: f32, value: impl Fn(usize) -> f64) -> Option<Self> {
        let values: Vec<f64> = (0..STEPS).map(value).collect();
        let steps = || (0..STEPS).rev().chain(0..STEPS).map(|i| values[i]);
        let signed: f64 = steps().sum();
        let magnitude: f64 = steps().map(f64::abs).sum();
        if !(signed > 0.0 && magnitude.is_finite()) {
            return None;
        }
        Some(SignedProfile {
            magnitude: StepProfile::new(radius, |i| values[i].abs()),
            negative: steps().map(|v| v < 0.0).collect(),
            ratio: (magnitude / signed) as f32,
        })
    }

    /// `∫|f| / ∫f`: the magnitude of every sample's weight (1 for a filter without negative
    /// steps).
    pub fn ratio(&self) -> f32 {
        self.ratio
    }

    /// An offset in `[-radius, radius]` with density proportional to `|f|`, from `u`, and
    /// whether `f` is negative there.
    pub fn sample(&self, u: f32) -> (f32, bool) {
        let (i, x) = self.magnitude.sample_step(u);
        (x, self.negative[i])
    }
}

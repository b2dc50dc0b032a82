//! A filter's values as Mitsuba 3 looks them up when it splats a sample: 31 values over `|x|` in
//! `[0, radius)`, each the filter at the start of its step, and zero from the radius on. Splatting
//! weighs every sample by these values, on each axis, for each pixel the filter reaches.
use super::step_profile::STEPS;

/// The values of a symmetric 1-D filter, tabulated for lookup by distance.
#[derive(Clone, Debug)]
pub struct FilterTable {
    /// Support radius in pixels.
    pub radius: f32,
    /// Steps per pixel of distance: `STEPS / radius`.
    scale: f32,
    /// The filter at `radius * i / STEPS` for `i < STEPS`; the last entry is zero.
    values: [f32; STEPS + 1],
}

impl FilterTable {
    /// The table of a filter of support `radius` whose value at `x = radius * i / STEPS` is
    /// `value(i)` (the same function the filter's sampling profile is built from).
    pub fn new(radius: f32, value: impl Fn(usize) -> f64) -> Self {
        let mut values = [0.0f32; STEPS + 1];
        for (i, v) in values.iter_mut().take(STEPS).enumerate() {
            *v = value(i) as f32;
        }
        FilterTable {
            radius,
            scale: STEPS as f32 / radius,
            values,
        }
    }

    /// The filter's value at distance `x` (either sign) from its centre: zero at and beyond the
    /// radius.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        // Clamped as a float first, so that the conversion is a plain truncation (`as usize`
        // saturates through a longer sequence); NaN indexes the last entry, zero. The integer
        // clamp only lets the compiler drop the bounds check.
        let i = (libm::fabsf(x) * self.scale).min(STEPS as f32) as u32 as usize;
        self.values[i.min(STEPS)]
    }
}

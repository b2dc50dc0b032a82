//! A phase function given as a table (`tabphase`, Mitsuba 3's): values at evenly spaced cosines
//! of the scattering angle from -1 (backward) to 1 (forward), linearly interpolated between
//! them. Parameters are read by `scene/src/media/phase.rs`.
//!
//! The cosine `c` here is between the direction of propagation (`-wi`) and `wo`, so the table's
//! last entry is forward scattering, as in Mitsuba 3. The table is normalised the way Mitsuba 3
//! normalises it: divided by its trapezoid-rule integral over [-1, 1] (which is the exact
//! integral of the piecewise-linear function), so that `p(c)` integrates to 1 over the cosine
//! and the density per steradian is `p(c) / (2 pi)` (uniform in azimuth).
//!
//! Sampling picks an interval by the table's cumulative distribution and inverts the linear
//! density inside it in closed form (the root of a quadratic), so it is exact for the
//! piecewise-linear density and every sample has weight 1.
use super::phase_sample::PhaseSample;
use crate::math::{sincos_turns, sqrt, Frame, PI};
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// Why a table cannot be a phase function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TableError {
    /// Fewer than two values.
    TooFew,
    /// The value at this index is negative or not finite.
    BadValue(usize),
    /// Every value is zero.
    NoMass,
}

/// A tabulated phase function over the cosine of the scattering angle.
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    /// Density over the cosine at the nodes `-1 + 2 i / (n - 1)` (integrates to 1 over [-1, 1]).
    density: Vec<f32>,
    /// Cumulative distribution at the nodes: 0 at the first, 1 at the last.
    cdf: Vec<f32>,
}

impl Tabulated {
    /// The phase function of `values` (at least two, finite, non-negative, not all zero).
    pub fn new(values: &[f32]) -> Result<Self, TableError> {
        if values.len() < 2 {
            return Err(TableError::TooFew);
        }
        if let Some(i) = values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(TableError::BadValue(i));
        }
        let h = 2.0 / (values.len() - 1) as f64;
        let mut cum = Vec::with_capacity(values.len());
        let mut total = 0.0f64;
        cum.push(0.0);
        for w in values.windows(2) {
            total += 0.5 * h * (f64::from(w[0]) + f64::from(w[1]));
            cum.push(total);
        }
        if !(total > 0.0) || !total.is_finite() {
            return Err(TableError::NoMass);
        }
        Ok(Tabulated {
            density: values
                .iter()
                .map(|v| (f64::from(*v) / total) as f32)
                .collect(),
            cdf: cum.iter().map(|c| (c / total) as f32).collect(),
        })
    }
    /// Node spacing in cosine.
    #[inline]
    fn step(&self) -> f32 {
        2.0 / (self.density.len() - 1) as f32
    }
    /// The density over the cosine `c` (0 outside [-1, 1]).
    #[inline]
    pub fn density_cos(&self, c: f32) -> f32 {
        if !(-1.0..=1.0).contains(&c) {
            return 0.0;
        }
        let last = self.density.len() - 1;
        let x = (c + 1.0) / self.step();
        let i = (x as usize).min(last - 1);
        let t = (x - i as f32).clamp(0.0, 1.0);
        self.density[i] + t * (self.density[i + 1] - self.density[i])
    }
    /// Value (and density) per steradian of scattering from `wi` toward `wo`.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.density_cos(-wi.dot(wo)) * (0.5 / PI)
    }
    /// Samples a cosine from the table's distribution.
    fn sample_cos(&self, u: f32) -> f32 {
        // The last node whose cumulative value is <= u, skipping empty intervals.
        let last = self.density.len() - 1;
        let i = self.cdf.partition_point(|c| *c <= u).clamp(1, last) - 1;
        let h = self.step();
        let (a, b) = (self.density[i], self.density[i + 1]);
        // Mass to cover inside the interval, in units of its width.
        let r = ((u - self.cdf[i]) / h).max(0.0);
        // a t + (b - a) t^2 / 2 = r, in the form that keeps its digits for either sign of b - a.
        let disc = (a * a + 2.0 * (b - a) * r).max(0.0);
        let denom = a + sqrt(disc);
        let t = if denom > 0.0 { 2.0 * r / denom } else { 0.0 };
        (-1.0 + (i as f32 + t.clamp(0.0, 1.0)) * h).clamp(-1.0, 1.0)
    }
    /// Samples `wo` for `wi` from two uniform numbers (weight 1).
    pub fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        let c = self.sample_cos(u.x);
        let sin = sqrt((1.0 - c * c).max(0.0));
        let (sp, cp) = sincos_turns(u.y);
        let wo = Frame::from_normal(-wi).to_world(Vec3::new(sin * cp, sin * sp, c));
        PhaseSample {
            wo,
            pdf: self.density_cos(c) * (0.5 / PI),
            weight: 1.0,
        }
    }
}

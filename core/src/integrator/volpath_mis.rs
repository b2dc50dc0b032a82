//! How the volumetric path tracers weigh their estimates over the colour channels and between
//! emitter sampling and phase-function or BSDF sampling: `volpath`'s separate weights, or
//! `volpathmis`'s joint ones (Mitsuba 3's `volpathmis`, after Miller et al. 2019, "A null-scattering
//! path integral formulation of light transport").
//!
//! A path draws its free flights from one channel `c` chosen uniformly when it starts (see
//! `medium::free_flight`); `R_k` is the ratio of the path's density had channel `k` been chosen
//! to its density with `c`, up to the vertex that samples an emitter (the last real scattering
//! vertex). For the segment from that vertex to the light, `S_k` is the probability that channel
//! `k`'s free flights pass it (for homogeneous media, its transmittance `exp(-sigma_k d)`).
//!
//! - `volpath` weighs the channels by `1 / mean_k R` and the two directional strategies by the
//!   power heuristic over the directional densities alone (`p_light`, `p_dir`).
//! - `volpathmis` weighs each contribution by the balance heuristic over all six strategies at
//!   once (three channels, times emitter or directional sampling), whose densities are
//!   `R_k p_light` and `R_k p_dir S_k` up to the common factor: a contribution `F` (the channel's
//!   value of the whole path, transmittance included) counts `F / mean_k (R_k (p_light + p_dir
//!   S_k))` times the density of the strategy that found it. Emitter sampling evaluates the
//!   transmittance exactly instead of sampling it as Mitsuba 3 does, so its density has no
//!   `S_k`; the expectation is the same. Where the segment crosses a heterogeneous medium, whose
//!   pass probability depends on the null collisions drawn, both strategies fall back to
//!   `volpath`'s weights (the same segment decides for both, so the weights still sum to one).
//!   Without spectral MIS (`use_spectral_mis` false) the chosen channel's density stands alone:
//!   `mean_k R_k x_k` becomes `x_c`.
use crate::Color;

/// The weighting of a volumetric path tracer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MediumMis {
    /// `volpath`: channels by the balance heuristic, directions by the power heuristic.
    #[default]
    Separate,
    /// `volpathmis`: the balance heuristic over channels and directional strategies jointly.
    Joint {
        /// Whether the channels are weighed together (`use_spectral_mis`), or the chosen one
        /// alone.
        spectral: bool,
    },
}

impl MediumMis {
    /// Whether the channels are combined by the balance heuristic.
    #[inline]
    pub fn spectral(self) -> bool {
        match self {
            MediumMis::Separate => true,
            MediumMis::Joint { spectral } => spectral,
        }
    }
    /// `mean_k R_k x_k` (spectral) or `x_c` (the chosen channel alone).
    #[inline]
    fn channel_mean(self, ratios: Color, x: Color, channel: usize) -> f32 {
        if self.spectral() {
            (ratios * x).element_sum() / 3.0
        } else {
            x[channel.min(2)]
        }
    }
    /// The factor on an emitter-sampled contribution (throughput times scattering value times
    /// the light's sample weight) under the joint weights: `p_light / mean_k (R_k (p_light + p_dir
    /// S_k))`, with `ratios` the path's `R` at the vertex and `pass` the segment's `S`. `p_dir`
    /// is 0 for a light no direction can hit (a delta light).
    #[inline]
    pub(super) fn emitter_factor(
        self,
        ratios: Color,
        channel: usize,
        p_light: f32,
        p_dir: f32,
        pass: Color,
    ) -> f32 {
        let m = self.channel_mean(ratios, Color::splat(p_light) + pass * p_dir, channel);
        finite_or_zero(p_light / m)
    }
    /// The factor on a contribution found by following a sampled direction to an emitter
    /// (throughput times emitted radiance; the throughput divided by the chosen channel's
    /// densities `S_c` along the segment) under the joint weights: `S_c p_dir / mean_k (R_k
    /// (p_light + p_dir S_k))`, with `ratios` the `R` at the vertex the direction left.
    #[inline]
    pub(super) fn hit_factor(
        self,
        ratios: Color,
        channel: usize,
        p_light: f32,
        p_dir: f32,
        pass: Color,
    ) -> f32 {
        let m = self.channel_mean(ratios, Color::splat(p_light) + pass * p_dir, channel);
        finite_or_zero(pass[channel.min(2)] * p_dir / m)
    }
}

#[inline]
fn finite_or_zero(x: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

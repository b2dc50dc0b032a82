//! Free-flight sampling: the distance a path travels through a homogeneous medium before it
//! collides, when the extinction differs per colour channel, and the weights that make the
//! estimate unbiased for every channel at once.
//!
//! A path chooses one channel `c` uniformly when it starts and draws every distance from that
//! channel's exponential density `sigma_c exp(-sigma_c t)`. The estimate for channel `j` is then
//! weighted by the one-sample balance heuristic over the three channels, taken over the whole
//! path: `f_j / mean_k P_k`, where `P_k` is the product of the densities the path's distance
//! events would have had had channel `k` been chosen (a collision at `t`: `sigma_k exp(-sigma_k
//! t)`; passing a segment of length `t_max`: `exp(-sigma_k t_max)`) and `f_j` the product of the
//! events' values for channel `j` (`sigma_s,j exp(-sigma_j t)`, or `exp(-sigma_j t_max)`). The
//! integrator keeps `f_j / P_c` as its throughput and the ratios `P_k / P_c`
//! ([`ChannelRatios`]); their mean divides the throughput wherever light is added.
//!
//! Because channel `j`'s own strategy has weight `f_j / P_j <= albedo_j` per event, the combined
//! weight never exceeds 3 (times the albedos). Mitsuba 3.9.1's `volpath` divides by the chosen
//! channel's density alone (`f_j / P_c`): the same expectation, with weights that grow without
//! bound along a path when the channels' extinctions differ. With equal extinctions both give
//! weight `albedo` at a collision and 1 for a pass, and the ratios stay 1.
use crate::Color;

/// The outcome of one free-flight sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeFlight {
    /// Distance travelled: to the collision, or the whole segment when it passed.
    pub t: f32,
    /// Whether the path collided inside the segment (a real scattering event).
    pub scattered: bool,
    /// The event's value per channel: `sigma_s exp(-sigma_t t)` for a collision,
    /// `exp(-sigma_t t_max)` for a pass.
    pub value: Color,
    /// The event's density per channel had that channel been chosen: `sigma_t exp(-sigma_t t)`
    /// for a collision, `exp(-sigma_t t_max)` for a pass.
    pub pdf: Color,
}

impl FreeFlight {
    /// This event's weight alone, combined over the channels: `value / mean(pdf)` (zero
    /// where that mean is zero).
    #[inline]
    pub fn mixture_weight(&self) -> Color {
        let m = self.pdf.element_sum() / 3.0;
        if m > 0.0 {
            self.value / m
        } else {
            Color::ZERO
        }
    }
}

/// `exp(-sigma_t d)` per channel, exactly 1 where `sigma_t` is 0 (also for infinite `d`).
#[inline]
pub(super) fn transmittance(sigma_t: Color, d: f32) -> Color {
    let one = |s: f32| if s > 0.0 { libm::expf(-s * d) } else { 1.0 };
    Color::new(one(sigma_t.x), one(sigma_t.y), one(sigma_t.z))
}

/// Samples the distance to the next collision along a segment of length `t_max` (may be
/// infinite) through a medium of extinction `sigma_t` and scattering `sigma_s`, from channel
/// `channel`'s (0, 1 or 2) exponential and the uniform number `u`.
#[inline]
pub fn sample_free_flight(
    sigma_t: Color,
    sigma_s: Color,
    t_max: f32,
    channel: usize,
    u: f32,
) -> FreeFlight {
    let s = sigma_t[channel.min(2)];
    let t = if s > 0.0 {
        -libm::log1pf(-u) / s
    } else {
        f32::INFINITY
    };
    if t < t_max {
        let tr = transmittance(sigma_t, t);
        FreeFlight {
            t,
            scattered: true,
            value: sigma_s * tr,
            pdf: sigma_t * tr,
        }
    } else {
        let tr = transmittance(sigma_t, t_max);
        FreeFlight {
            t: t_max,
            scattered: false,
            value: tr,
            pdf: tr,
        }
    }
}

/// A path's channel and its density ratios `P_k / P_c` (see the module header).
#[derive(Clone, Copy, Debug)]
pub struct ChannelRatios {
    /// The channel distances are drawn from.
    pub channel: usize,
    /// `P_k / P_c` per channel `k`.
    pub ratios: Color,
}

impl ChannelRatios {
    /// A path drawing distances from the channel `u` picks uniformly.
    #[inline]
    pub fn new(u: f32) -> Self {
        ChannelRatios {
            channel: ((u * 3.0) as usize).min(2),
            ratios: Color::ONE,
        }
    }
    /// Takes event `ff` into the ratios; returns the throughput factor `value / pdf_c` (zero
    /// when the chosen channel's density is zero, which a sampled event never has).
    #[inline]
    pub fn record(&mut self, ff: &FreeFlight) -> Color {
        let pc = ff.pdf[self.channel];
        if !(pc > 0.0) {
            return Color::ZERO;
        }
        self.ratios *= ff.pdf / pc;
        ff.value / pc
    }
    /// The factor that turns the path's throughput into its combined weight: `1 / mean_k(P_k /
    /// P_c)`.
    #[inline]
    pub fn weight(&self) -> f32 {
        let m = self.ratios.element_sum() / 3.0;
        if m > 0.0 && m.is_finite() {
            1.0 / m
        } else {
            0.0
        }
    }
}

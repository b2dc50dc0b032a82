//! Free-flight sampling: the distance a path travels through a homogeneous medium before it
//! collides, when the extinction differs per colour channel.
//!
//! One channel `k` is chosen uniformly and a distance drawn from its exponential density
//! `sigma_k exp(-sigma_k t)`. The distance's density is then the mixture over the three
//! channels, `mean_k sigma_k exp(-sigma_k t)` (or, for passing the whole segment, the mean
//! probability of passing, `mean_k exp(-sigma_k t_max)`), and the throughput is weighted by the
//! ratio of each channel's own term to that mean: a collision weighs
//! `sigma_s exp(-sigma_t t) / mean_k(sigma_k exp(-sigma_k t))`, a pass
//! `exp(-sigma_t t_max) / mean_k exp(-sigma_k t_max)`. This is the one-sample combination of the
//! three channels' strategies by the balance heuristic; the weights stay bounded (at most 3
//! times the albedo), where dividing by the chosen channel's density alone (Mitsuba 3.9.1's
//! `volpath`) has the same expectation but weights that grow without bound when the channels'
//! extinctions differ. With equal extinctions both reduce to weight `albedo` at a collision and
//! 1 for a pass.
use super::homogeneous::transmittance;
use crate::Color;

/// The outcome of one free-flight sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeFlight {
    /// Distance travelled: to the collision, or the whole segment when it passed.
    pub t: f32,
    /// Whether the path collided inside the segment (a real scattering event).
    pub scattered: bool,
    /// Throughput factor (see the module's header); zero when the sample cannot be weighed.
    pub weight: Color,
}

/// Samples the distance to the next collision along a segment of length `t_max` (may be
/// infinite) through a medium of extinction `sigma_t` and scattering `sigma_s`: `u_channel`
/// picks the channel, `u` the distance.
#[inline]
pub fn sample_free_flight(
    sigma_t: Color,
    sigma_s: Color,
    t_max: f32,
    u_channel: f32,
    u: f32,
) -> FreeFlight {
    let k = ((u_channel * 3.0) as usize).min(2);
    let s = sigma_t[k];
    let t = if s > 0.0 {
        -libm::log1pf(-u) / s
    } else {
        f32::INFINITY
    };
    if t < t_max {
        let tr = transmittance(sigma_t, t);
        let density = (sigma_t * tr).element_sum() / 3.0;
        let weight = if density > 0.0 {
            sigma_s * tr / density
        } else {
            Color::ZERO
        };
        FreeFlight {
            t,
            scattered: true,
            weight,
        }
    } else {
        let tr = transmittance(sigma_t, t_max);
        let p = tr.element_sum() / 3.0;
        let weight = if p > 0.0 { tr / p } else { Color::ZERO };
        FreeFlight {
            t: t_max,
            scattered: false,
            weight,
        }
    }
}

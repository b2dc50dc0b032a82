//! What sampling any BSDF returns: a direction with its Monte Carlo weight. Its own file so that
//! the BSDF kinds take it from below instead of from the enum that holds them.
use crate::Color;
use glam::Vec3;

/// A sampled direction with its Monte Carlo weight.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Sampled direction (local).
    pub wo: Vec3,
    /// `f(wi, wo) |cos theta_o| / pdf`: the throughput factor.
    pub weight: Color,
    /// Solid-angle density (for a delta component: its discrete probability).
    pub pdf: f32,
    /// Whether a delta (specular) component was sampled.
    pub delta: bool,
    /// Relative index of refraction `eta_t / eta_i` of a refraction (1 for reflection), for
    /// Russian roulette to see through the radiance scaling.
    pub eta: f32,
}

impl BsdfSample {
    /// A sample of a delta component toward `wo` that keeps the medium (`eta` 1): its
    /// throughput `weight` and discrete probability `pdf`.
    #[inline]
    pub(crate) fn delta(wo: Vec3, weight: Color, pdf: f32) -> BsdfSample {
        BsdfSample {
            wo,
            weight,
            pdf,
            delta: true,
            eta: 1.0,
        }
    }

    /// A sample of a smooth (non-delta) reflection toward `wo`, weighted `f / pdf`; `None`
    /// unless `wo` is in the upper hemisphere and `pdf` is positive.
    #[inline]
    pub(crate) fn smooth_reflection(wo: Vec3, f: Color, pdf: f32) -> Option<BsdfSample> {
        if !(wo.z > 0.0 && pdf > 0.0) {
            return None;
        }
        Some(BsdfSample {
            wo,
            weight: f / pdf,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}

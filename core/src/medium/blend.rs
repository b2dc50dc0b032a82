//! A blend of two phase functions (`blendphase`, Mitsuba 3's): `(1 - w) p0 + w p1` for a weight
//! `w` in [0, 1] that is the same everywhere (Mitsuba 3 reads it as a volume; the loader,
//! `scene/src/media/phase.rs`, takes a constant only). `w = 0` is the first nested function
//! alone, `w = 1` the second.
//!
//! Sampling picks the second function with probability `w` (reusing the first uniform number,
//! stretched back to [0, 1)) and samples it; the density is the mixture's, and the weight is the
//! mixture's value over that density, which is 1 when each part is sampled exactly.
use super::phase_model::PhaseModel;
use super::phase_sample::PhaseSample;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// Two phase functions mixed by a constant weight.
#[derive(Clone, Debug, PartialEq)]
pub struct Blend<P> {
    /// Weight of the second function, in [0, 1].
    pub weight: f32,
    /// The function weighted by `1 - weight`.
    pub first: Box<P>,
    /// The function weighted by `weight`.
    pub second: Box<P>,
}

impl<P: PhaseModel> Blend<P> {
    /// Value of scattering from `wi` toward `wo`.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        let w = self.weight;
        (1.0 - w) * self.first.eval(wi, wo) + w * self.second.eval(wi, wo)
    }
    /// Density of sampling `wo` for `wi`.
    #[inline]
    pub fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let w = self.weight;
        (1.0 - w) * self.first.pdf(wi, wo) + w * self.second.pdf(wi, wo)
    }
    /// Samples `wo` for `wi` from two uniform numbers.
    pub fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        let w = self.weight;
        let pick_second = u.x < w;
        let (chosen, other, w_chosen) = if pick_second {
            (&self.second, &self.first, w)
        } else {
            (&self.first, &self.second, 1.0 - w)
        };
        let ux = if pick_second {
            u.x / w
        } else {
            (u.x - w) / (1.0 - w)
        };
        let s = chosen.sample(wi, Vec2::new(ux.clamp(0.0, 1.0 - f32::EPSILON / 2.0), u.y));
        if w_chosen >= 1.0 {
            return s;
        }
        let pdf = w_chosen * s.pdf + (1.0 - w_chosen) * other.pdf(wi, s.wo);
        let value = w_chosen * s.weight * s.pdf + (1.0 - w_chosen) * other.eval(wi, s.wo);
        PhaseSample {
            wo: s.wo,
            pdf,
            weight: if pdf > 0.0 { value / pdf } else { 0.0 },
        }
    }
}

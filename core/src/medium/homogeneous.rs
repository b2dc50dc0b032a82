//! A homogeneous medium (`homogeneous`, Mitsuba 3's): extinction `sigma_t` constant throughout,
//! per colour channel, an albedo (a constant, or a volume looked up where a collision happens),
//! and one phase function.
//!
//! Light travelling a distance `d` through it keeps `exp(-sigma_t d)` (Beer-Lambert); at a
//! collision a fraction `albedo` scatters (`sigma_s = albedo sigma_t`) and the rest is
//! absorbed. The loader folds Mitsuba's `scale` into `sigma_t`. With the SGGX phase function
//! the extinction along direction `w` is `sigma_t sigma(w)`, the flakes' projected area (as in
//! Mitsuba 3), so free flights and transmittance depend on the ray's direction.
use super::free_flight::{sample_free_flight, transmittance, FreeFlight};
use super::phase::PhaseFunction;
use super::volume::{Volume, VolumeData};
use crate::Color;
use glam::Vec3;

/// A medium of constant extinction.
#[derive(Clone, Debug)]
pub struct Homogeneous {
    /// Extinction coefficient per channel, in inverse scene units (scale applied), >= 0.
    pub sigma_t: Color,
    /// Single-scattering albedo per channel.
    pub albedo: Volume,
    /// How scattered light is distributed over directions.
    pub phase: PhaseFunction,
    /// Whether scattering events in it sample emitters (shadow rays from inside the medium).
    pub sample_emitters: bool,
}

impl Homogeneous {
    /// Extinction along unit direction `d` (either sign): `sigma_t`, times the flakes'
    /// projected area for the SGGX phase function.
    #[inline]
    pub fn sigma_t_along(&self, d: Vec3) -> Color {
        match &self.phase {
            PhaseFunction::Sggx(s) => self.sigma_t * s.s.projected_area(d),
            _ => self.sigma_t,
        }
    }
    /// Fraction of light kept over a distance `dist` (which may be infinite) along unit
    /// direction `d`: `exp(-sigma_t dist)` per channel, 1 where `sigma_t` is 0.
    #[inline]
    pub fn transmittance(&self, d: Vec3, dist: f32) -> Color {
        transmittance(self.sigma_t_along(d), dist)
    }
    /// A free flight along the ray `o + t d` (`d` of unit length) up to `t_max`, from channel
    /// `channel`'s exponential and the uniform number `u`; the albedo is looked up at the
    /// collision.
    #[inline]
    pub fn sample_flight(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        channel: usize,
        u: f32,
    ) -> FreeFlight {
        let sigma_t = self.sigma_t_along(d);
        match &self.albedo.data {
            VolumeData::Constant(a) => sample_free_flight(sigma_t, *a * sigma_t, t_max, channel, u),
            VolumeData::Grid(_) => {
                let mut ff = sample_free_flight(sigma_t, sigma_t, t_max, channel, u);
                if ff.scattered {
                    ff.value *= self.albedo.eval(o + d * ff.t);
                }
                ff
            }
        }
    }
}

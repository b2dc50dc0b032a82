//! Spot light: a point light whose intensity falls off with the angle from its axis (a delta
//! light), exactly as Mitsuba 3's `spot`.
//!
//! Scene parameters (`<emitter type="spot">`): `intensity` (rgb, default 1, W/sr: the intensity
//! on the axis), `cutoff_angle` (float, degrees, default 20, in (0, 180]: no light beyond it),
//! `beam_width` (float, degrees, default `cutoff_angle * 3/4`, in [0, cutoff_angle]: full
//! intensity within it), `to_world` (transform; the light sits at its translation and shines
//! along its local +z). No `texture`.
//!
//! Falloff at angle `theta` from the axis (Mitsuba 3's, checked against Mitsuba 3.9.1 itself):
//! 1 for `theta <= beam_width`, `(cutoff - theta) / (cutoff - beam_width)` (linear in the angle)
//! between the two, 0 for `theta >= cutoff`.
use super::sample::EmitterSample;
use crate::geometry::Interaction;
use crate::math::{acos, sqrt, Norm, Transform, PI};
use crate::Color;
use glam::{Mat3, Vec3};

/// A spot light.
#[derive(Clone, Debug)]
pub struct SpotLight {
    /// Position.
    pub position: Vec3,
    /// World to light-local directions (the inverse of `to_world`'s linear part).
    pub to_local: Mat3,
    /// Radiant intensity on the axis.
    pub intensity: Color,
    /// Cutoff angle (radians).
    pub cutoff: f32,
    /// Beam width (radians).
    pub beam: f32,
    cos_cutoff: f32,
    cos_beam: f32,
    inv_transition: f32,
}

impl SpotLight {
    /// A spot light at `to_world`'s origin shining along its +z; angles in degrees (the caller
    /// checks `0 < cutoff <= 180` and `0 <= beam <= cutoff`).
    pub fn new(intensity: Color, cutoff_deg: f32, beam_deg: f32, to_world: &Transform) -> Self {
        let cutoff = cutoff_deg.to_radians();
        let beam = beam_deg.to_radians().min(cutoff);
        let width = cutoff - beam;
        SpotLight {
            position: to_world.point(Vec3::ZERO),
            to_local: Mat3::from_mat4(to_world.inv),
            intensity,
            cutoff,
            beam,
            cos_cutoff: libm::cosf(cutoff),
            cos_beam: libm::cosf(beam),
            inv_transition: if width > 0.0 { 1.0 / width } else { 0.0 },
        }
    }

    /// Fraction of the axis intensity emitted along the local unit direction `d`.
    #[inline]
    pub fn falloff(&self, d: Vec3) -> f32 {
        let cos_t = d.z;
        if !(cos_t > self.cos_cutoff) {
            0.0
        } else if cos_t >= self.cos_beam {
            1.0
        } else {
            ((self.cutoff - acos(cos_t.min(1.0))) * self.inv_transition).clamp(0.0, 1.0)
        }
    }

    /// The direction to the light, with irradiance `I falloff / d^2`.
    pub fn sample(&self, it: &Interaction) -> Option<EmitterSample> {
        let d = self.position - it.p;
        let dist2 = d.length_squared();
        if !(dist2 > 0.0) {
            return None;
        }
        let wo = d / sqrt(dist2);
        let local = (self.to_local * -wo).unit_or_zero();
        let falloff = self.falloff(local);
        if !(falloff > 0.0) {
            return None;
        }
        Some(EmitterSample {
            wo,
            target: Some(self.position),
            weight: self.intensity * (falloff / dist2),
            pdf: 1.0,
            delta: true,
        })
    }

    /// Integral of the falloff over the sphere of directions (sr): `2 pi (1 - (sin c - sin b) /
    /// (c - b))` for cutoff `c` and beam width `b`, `2 pi (1 - cos c)` when they coincide.
    pub(crate) fn solid_angle(&self) -> f32 {
        let (c, b) = (self.cutoff, self.beam);
        let frac = if c - b > 1e-3 {
            1.0 - (libm::sinf(c) - libm::sinf(b)) / (c - b)
        } else {
            1.0 - libm::cosf(0.5 * (c + b))
        };
        2.0 * PI * frac.max(0.0)
    }
}

//! Spot light: a point light whose intensity falls off with the angle from its axis (a delta
//! light), exactly as Mitsuba 3's `spot`.
//!
//! Scene parameters (`<emitter type="spot">`): `intensity` (rgb, default 1, W/sr: the intensity
//! on the axis), `cutoff_angle` (float, degrees, default 20, in (0, 180]: no light beyond it),
//! `beam_width` (float, degrees, default `cutoff_angle * 3/4`, in [0, cutoff_angle]: full
//! intensity within it), `to_world` (transform; the light sits at its translation and shines
//! along its local +z), `texture` (optional, a bitmap or checkerboard, never a constant: an
//! image projected into the cone).
//!
//! Falloff at angle `theta` from the axis (Mitsuba 3's, checked against Mitsuba 3.9.1 itself):
//! 1 for `theta <= beam_width`, `(cutoff - theta) / (cutoff - beam_width)` (linear in the angle)
//! between the two, 0 for `theta >= cutoff`.
//!
//! Texture (Mitsuba 3.9.1's, checked against its `sample_direction`): the intensity along the
//! local direction `d` is multiplied by the texture at `u = 1/2 + d.x / (2 d.z tan(cutoff))`,
//! `v = 1/2 + d.y / (2 d.z tan(cutoff))`, so the cone is inscribed in the texture's unit square
//! (local +x toward `u = 1`, local +y toward `v = 1`, the image's last row), and the falloff
//! still applies. The texture's values are used as they are (no normalisation). Without a
//! texture nothing is multiplied, so untextured spots keep their bits.
use super::sample::{luminance, EmitterSample};
use crate::geometry::Interaction;
use crate::math::{acos, sqrt, Norm, Transform, PI};
use crate::texture::Texture;
use crate::Color;
use glam::{Mat3, Vec2, Vec3};

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
    /// The image projected into the cone, if any (see the header for its mapping).
    pub texture: Option<Texture>,
    tan_cutoff: f32,
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
            texture: None,
            tan_cutoff: libm::tanf(cutoff),
            cos_cutoff: libm::cosf(cutoff),
            cos_beam: libm::cosf(beam),
            inv_transition: if width > 0.0 { 1.0 / width } else { 0.0 },
        }
    }

    /// The same light projecting `texture` into its cone.
    pub fn with_texture(self, texture: Texture) -> Self {
        SpotLight {
            texture: Some(texture),
            ..self
        }
    }

    /// Where the local direction `d` (inside the cone) looks the texture up.
    #[inline]
    pub(crate) fn texture_uv(&self, d: Vec3) -> Vec2 {
        let k = 0.5 / (d.z * self.tan_cutoff);
        Vec2::new(0.5 + d.x * k, 0.5 + d.y * k)
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
        let weight = match &self.texture {
            None => self.intensity * (falloff / dist2),
            Some(t) => self.intensity * t.eval(self.texture_uv(local)) * (falloff / dist2),
        };
        Some(EmitterSample {
            wo,
            target: Some(self.position),
            weight,
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

    /// Luminance of the intensity on the axis, times the texture's mean where there is one: a
    /// power estimate, not a lookup.
    pub fn luminance(&self) -> f32 {
        match &self.texture {
            None => luminance(self.intensity),
            Some(t) => luminance(self.intensity * t.mean_value()),
        }
    }
}

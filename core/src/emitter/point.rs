//! Point light: isotropic intensity from one point (a delta light).
//!
//! Scene parameters (`<emitter type="point">`): `intensity` (rgb, default 1, W/sr), `position`
//! (point, default 0,0,0) or `to_world` (its translation is the position).
use super::sample::EmitterSample;
use crate::geometry::Interaction;
use crate::math::sqrt;
use crate::Color;
use glam::Vec3;

/// An isotropic point light.
#[derive(Clone, Debug)]
pub struct PointLight {
    /// Position.
    pub position: Vec3,
    /// Radiant intensity.
    pub intensity: Color,
}

impl PointLight {
    /// The only direction there is, with irradiance falloff `1 / d^2`.
    pub fn sample(&self, it: &Interaction) -> Option<EmitterSample> {
        let d = self.position - it.p;
        let dist2 = d.length_squared();
        if !(dist2 > 0.0) {
            return None;
        }
        let wo = d / sqrt(dist2);
        Some(EmitterSample {
            wo,
            target: Some(self.position),
            weight: self.intensity / dist2,
            pdf: 1.0,
            delta: true,
        })
    }
}

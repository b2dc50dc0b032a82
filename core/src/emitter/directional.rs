//! Directional light: parallel light from infinitely far away (a delta light in direction), as
//! Mitsuba 3's `directional`.
//!
//! Scene parameters (`<emitter type="directional">`): `irradiance` (rgb, default 1, W/m^2 on a
//! surface facing the light), `direction` (vector: where the light travels to) or `to_world`
//! (transform: the light travels along its local +z; default identity, so along +z). Not both.
//!
//! Shadow rays go to infinity. For light selection by power it counts as `irradiance` falling
//! on the disk of the scene's bounding sphere, `pi r^2 E`.
use super::sample::EmitterSample;
use crate::geometry::Interaction;
use crate::Color;
use glam::Vec3;

/// A directional light.
#[derive(Clone, Debug)]
pub struct DirectionalLight {
    /// Unit direction the light travels along (from the light toward the scene).
    pub direction: Vec3,
    /// Irradiance on a surface perpendicular to `direction`.
    pub irradiance: Color,
}

impl DirectionalLight {
    /// The only direction there is, `-direction`.
    pub fn sample(&self, _it: &Interaction) -> Option<EmitterSample> {
        Some(EmitterSample {
            wo: -self.direction,
            target: None,
            weight: self.irradiance,
            pdf: 1.0,
            delta: true,
        })
    }
}

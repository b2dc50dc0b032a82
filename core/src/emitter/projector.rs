//! Projector: a point light that projects an image through a pinhole frustum (a delta light),
//! as Mitsuba 3's `projector`, the reciprocal of its `perspective` sensor.
//!
//! Scene parameters are declared with the loader, in `scene/src/emitters/projector.rs`.
//!
//! Conventions (Mitsuba 3.9.1's, checked against its `sample_direction`): in the light's local
//! frame (`to_world`'s inverse) the frustum looks along +z with +y up; a point `p` with
//! `p.z > 0` sees the texture at `u = 1/2 - p.x / (2 p.z tan_x)`, `v = 1/2 - p.y / (2 p.z
//! tan_y)` (the image's first column toward local +x, its first row toward +y, as the
//! perspective camera sees them), and nothing outside `[0, 1]^2`. `tan_x` and `tan_y` are half
//! the image plane's extents at depth 1, from the field of view and the texture's aspect ratio
//! (its resolution; 1x1 for a constant or a checkerboard).
//!
//! The light arriving at `p` is `E(u, v) pi scale / (p.z^2 cos)`, where `cos` is the cosine
//! between the light's axis (`to_world` applied to +z, not renormalised) and the direction to
//! `p`: since `dist^2 cos^3 = p.z^2 cos` for an unscaled frame, a surface facing the projector
//! at depth 1 receives irradiance `pi scale E` at every point of the image, whatever its place
//! in the frustum. The power is therefore `pi scale` times the texture's mean times the image
//! plane's area at depth 1, `4 tan_x tan_y`.
use super::sample::{luminance, EmitterSample};
use crate::geometry::Interaction;
use crate::math::{sqrt, Transform, PI};
use crate::texture::Texture;
use glam::{Mat4, Vec2, Vec3};

/// A projector light.
#[derive(Clone, Debug)]
pub struct Projector {
    /// Position (the pinhole).
    pub position: Vec3,
    /// World to light-local points.
    to_local: Mat4,
    /// `to_world` applied to the local +z (not renormalised, as Mitsuba 3 uses it).
    axis: Vec3,
    /// Irradiance on the image plane at depth 1, over the image's unit square, before `pi
    /// scale`.
    pub irradiance: Texture,
    /// Factor on the irradiance.
    pub scale: f32,
    /// Half the image plane's width and height at depth 1.
    half: Vec2,
}

impl Projector {
    /// A projector at `to_world`'s origin looking along its +z, whose image plane at depth 1
    /// spans `[-half.x, half.x] x [-half.y, half.y]`.
    pub fn new(irradiance: Texture, scale: f32, half: Vec2, to_world: &Transform) -> Self {
        Projector {
            position: to_world.point(Vec3::ZERO),
            to_local: to_world.inv,
            axis: to_world.vector(Vec3::Z),
            irradiance,
            scale,
            half,
        }
    }

    /// The texture coordinates that the light-local point `p` sees, if it is in the frustum.
    #[inline]
    pub fn uv(&self, p: Vec3) -> Option<Vec2> {
        if !(p.z > 0.0) {
            return None;
        }
        let uv = Vec2::new(
            0.5 - 0.5 * p.x / (p.z * self.half.x),
            0.5 - 0.5 * p.y / (p.z * self.half.y),
        );
        let inside = uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0;
        inside.then_some(uv)
    }

    /// The direction to the light, with the irradiance the projection gives it.
    pub fn sample(&self, it: &Interaction) -> Option<EmitterSample> {
        let local = self.to_local.transform_point3(it.p);
        let uv = self.uv(local)?;
        let d = self.position - it.p;
        let dist2 = d.length_squared();
        if !(dist2 > 0.0) {
            return None;
        }
        let wo = d / sqrt(dist2);
        let denom = local.z * local.z * -self.axis.dot(wo);
        if !(denom > 0.0) {
            return None;
        }
        let weight = self.irradiance.eval(uv) * (PI * self.scale / denom);
        weight.is_finite().then_some(EmitterSample {
            wo,
            target: Some(self.position),
            weight,
            pdf: 1.0,
            delta: true,
        })
    }

    /// Luminance of the intensity on the axis for the texture's mean (`pi scale E`): a
    /// strength estimate, not a lookup.
    pub(crate) fn axis_luminance(&self) -> f32 {
        PI * self.scale * luminance(self.irradiance.mean_value())
    }

    /// Emitted power (luminance): the mean irradiance at depth 1 times the image plane's area
    /// there.
    pub fn power(&self) -> f32 {
        self.axis_luminance() * 4.0 * self.half.x * self.half.y
    }
}

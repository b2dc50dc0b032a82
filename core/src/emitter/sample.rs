//! What every kind of emitter shares: the part of the scene it samples in ([`EmitterCtx`]), the
//! sample it returns ([`EmitterSample`]) and the luminance its power is measured in. Its own
//! file so that the emitter kinds take these from below instead of from the enum that holds
//! them.
use crate::geometry::{Disk, Shape};
use crate::Color;
use glam::Vec3;

/// What emitters need to know of the scene while sampling.
pub struct EmitterCtx<'a> {
    /// All shapes.
    pub shapes: &'a [Shape],
    /// All disks.
    pub disks: &'a [Disk],
    /// Centre of the scene's bounding sphere.
    pub scene_center: Vec3,
    /// Radius of the scene's bounding sphere.
    pub scene_radius: f32,
}

/// Luminance (Rec. 709) of a linear RGB colour.
#[inline]
pub fn luminance(c: Color) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// A light sample seen from a reference point.
#[derive(Clone, Copy, Debug)]
pub struct EmitterSample {
    /// Unit direction from the reference point toward the light.
    pub wo: Vec3,
    /// Where the shadow segment ends (already offset off the light's surface), or `None` for a
    /// light at infinity (shadow ray of unbounded extent along `wo`).
    pub target: Option<Vec3>,
    /// Emitted radiance arriving along `-wo`, divided by `pdf` (excludes light selection).
    pub weight: Color,
    /// Solid-angle density (1 for delta lights).
    pub pdf: f32,
    /// Whether the light is a delta distribution (a point, or a single direction): no other
    /// strategy can find it.
    pub delta: bool,
}

//! `mesh_attribute`: a texture whose value is a mesh's named per-vertex or per-face attribute
//! at the point hit (Mitsuba 3's plugin of that name), times `scale`.
//!
//! As in Mitsuba 3's RGB variants: a colour lookup of a one-component attribute gives it on
//! every channel and of a three-component one its three values; a scalar lookup gives a
//! one-component attribute's value. Any other pairing, a mesh without the attribute (the loader
//! refuses that), or a lookup without the triangle hit gives zero. The loader
//! accepts the texture only as a BSDF parameter, whose lookups are given the hit.
use crate::geometry::ShadingPoint;
use crate::Color;
use alloc::string::String;

/// A mesh attribute read as a texture.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttributeTexture {
    /// The attribute's name (`vertex_*` or `face_*`).
    pub name: String,
    /// Factor on the value.
    pub scale: f32,
}

impl MeshAttributeTexture {
    /// The colour at `at`.
    #[inline]
    pub fn eval(&self, at: ShadingPoint) -> Color {
        match at.site().and_then(|s| s.attribute(&self.name)) {
            Some((1, v)) => Color::splat(v.x * self.scale),
            Some((3, v)) => v * self.scale,
            _ => Color::ZERO,
        }
    }
    /// The scalar at `at`.
    #[inline]
    pub fn eval_1(&self, at: ShadingPoint) -> f32 {
        match at.site().and_then(|s| s.attribute(&self.name)) {
            Some((1, v)) => v.x * self.scale,
            _ => 0.0,
        }
    }
}

//! Where on a surface a BSDF is asked: the texture coordinates and, for a model that tilts its
//! frame by a height field (`bumpmap`), the surface's local differential geometry.
//!
//! Every BSDF call takes one by value: sixteen bytes (the coordinates and a reference to the
//! partials, present only where the model reads them), so that the calls of ordinary models
//! cost what they cost with bare coordinates. Tests and tools that know only texture
//! coordinates convert a `Vec2` (`From<Vec2>`); a bump map without partials uses the flat unit
//! parametrisation `dp/du = x`, `dp/dv = y`, geometric normal `z` ([`Partials::FLAT`]).
use glam::{Vec2, Vec3};

/// The position's partials and the geometric normal, in the local shading frame (normal = +z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Partials {
    /// Position's derivative along u.
    pub dp_du: Vec3,
    /// Position's derivative along v.
    pub dp_dv: Vec3,
    /// Unit geometric normal.
    pub ng: Vec3,
}

impl Partials {
    /// The flat unit parametrisation of the shading plane.
    pub const FLAT: Partials = Partials {
        dp_du: Vec3::X,
        dp_dv: Vec3::Y,
        ng: Vec3::Z,
    };
}

/// Texture coordinates and, where a model reads them, the local partials at a shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingPoint<'a> {
    /// Texture coordinates.
    pub uv: Vec2,
    /// The partials, when the caller found them (only for models that read them).
    pub partials: Option<&'a Partials>,
}

impl ShadingPoint<'_> {
    /// The partials, or the flat unit parametrisation without them.
    #[inline]
    pub fn partials_or_flat(&self) -> Partials {
        self.partials.copied().unwrap_or(Partials::FLAT)
    }
}

impl From<Vec2> for ShadingPoint<'_> {
    #[inline]
    fn from(uv: Vec2) -> Self {
        ShadingPoint { uv, partials: None }
    }
}

//! Where on a surface a BSDF is asked: the texture coordinates and, for a model that tilts its
//! frame by a height field (`bumpmap`) or reads a mesh's attributes (`mesh_attribute`), the
//! surface's local differential geometry and the triangle hit.
//!
//! Every BSDF call takes one by value: twenty-four bytes (the coordinates, a reference to the
//! partials, present only where the model reads them, and one to the vertex's
//! [`LookupMemo`], which spares repeated image lookups), so that the calls of ordinary models
//! cost what they cost with bare coordinates. Tests and tools that know only texture
//! coordinates convert a `Vec2` (`From<Vec2>`); a bump map without partials uses the flat unit
//! parametrisation `dp/du = x`, `dp/dv = y`, geometric normal `z` ([`Partials::FLAT`]).
use super::{LookupMemo, MeshSite};
use glam::{Vec2, Vec3};

/// The position's partials and the geometric normal, in the local shading frame (normal = +z),
/// and, on a mesh, the triangle and barycentric coordinates hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Partials<'a> {
    /// Position's derivative along u.
    pub dp_du: Vec3,
    /// Position's derivative along v.
    pub dp_dv: Vec3,
    /// Unit geometric normal.
    pub ng: Vec3,
    /// The triangle hit, on a mesh (what `mesh_attribute` textures read).
    pub site: Option<MeshSite<'a>>,
}

impl Partials<'_> {
    /// The flat unit parametrisation of the shading plane.
    pub const FLAT: Partials<'static> = Partials {
        dp_du: Vec3::X,
        dp_dv: Vec3::Y,
        ng: Vec3::Z,
        site: None,
    };
}

/// Texture coordinates and, where a model reads them, the local partials at a shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingPoint<'a> {
    /// Texture coordinates.
    pub uv: Vec2,
    /// The partials, when the caller found them (only for models that read them).
    pub partials: Option<&'a Partials<'a>>,
    /// Where image lookups at this point are remembered (the path loop's vertices; `None`
    /// elsewhere): see [`LookupMemo`].
    pub memo: Option<&'a LookupMemo>,
}

impl<'a> ShadingPoint<'a> {
    /// The partials, or the flat unit parametrisation without them.
    #[inline]
    pub fn partials_or_flat(&self) -> Partials<'a> {
        self.partials.copied().unwrap_or(Partials::FLAT)
    }
    /// The mesh triangle hit, when the caller found it.
    #[inline]
    pub fn site(&self) -> Option<MeshSite<'a>> {
        self.partials.and_then(|p| p.site)
    }
}

/// A borrowed shading point, copied where it is used: callers pass `&at` to the models so that
/// the copy is made field by field inside the call, not by one wide load of fields stored a
/// moment before (which the CPU cannot forward from the narrower stores, and stalls on).
impl<'a> From<&ShadingPoint<'a>> for ShadingPoint<'a> {
    #[inline(always)]
    fn from(at: &ShadingPoint<'a>) -> Self {
        *at
    }
}

impl From<Vec2> for ShadingPoint<'_> {
    #[inline]
    fn from(uv: Vec2) -> Self {
        ShadingPoint {
            uv,
            partials: None,
            memo: None,
        }
    }
}

//! What a camera ray's hit is beyond [`crate::geometry::Interaction`], for the `aov`
//! integrator's derivative and index outputs (`Scene::surface_detail` finds it).
use glam::Vec3;

/// The `aov` outputs of a hit that [`crate::geometry::Interaction`] does not hold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceDetail {
    /// Position's derivative along u (world space).
    pub dp_du: Vec3,
    /// Position's derivative along v (world space).
    pub dp_dv: Vec3,
    /// The primitive's index in its shape, as Mitsuba numbers it.
    pub prim_index: u32,
    /// The shape's (or, for an instanced shape, the instance's) number in Mitsuba's list.
    pub shape_index: u32,
}

//! Small math building blocks: rays, frames, bounding boxes, transforms, floating-point bounds.
mod aabb;
mod arc;
mod float;
mod frame;
mod poly;
mod ray;
mod sqrt;
mod transform;
mod turns;

pub use aabb::Aabb;
pub use arc::{acos, atan2, atan2_turns};
pub(crate) use arc::{ACOS_COEFFS, ATAN_COEFFS, PI_LO};
pub use float::{gamma, next_down, next_up, offset_ray_origin};
pub use frame::Frame;
pub use ray::Ray;
pub use sqrt::{acos_f64, sqrt, sqrt4, sqrt_f64, Norm};
pub use transform::Transform;
pub use turns::sincos_turns;

/// Pi as f32.
pub const PI: f32 = core::f32::consts::PI;
/// 1 / pi.
pub const INV_PI: f32 = core::f32::consts::FRAC_1_PI;
/// 1 / (2 pi).
pub(crate) const INV_TWO_PI: f32 = 0.5 * core::f32::consts::FRAC_1_PI;
/// 1 / (4 pi).
pub(crate) const INV_FOUR_PI: f32 = 0.25 * core::f32::consts::FRAC_1_PI;

/// `sqrt(max(x, 0))`: safe against tiny negative rounding errors.
#[inline]
pub(crate) fn safe_sqrt(x: f32) -> f32 {
    sqrt(x.max(0.0))
}

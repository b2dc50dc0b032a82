//! The pinhole projection of Mitsuba 3's `perspective` sensor (and the one under `thinlens`'s
//! lens): film positions to directions in camera space, where the camera looks along local +z
//! with +y up and local +x to the image's left.
//!
//! Scene parameters are declared with the loader, in `scene/src/sensor.rs`: `fov` and
//! `fov_axis` (or `focal_length`), `near_clip`, `far_clip` and the principal point offsets,
//! which shift the image plane by a fraction of the film's size as Mitsuba 3 does (a positive
//! `principal_point_offset_x` makes pixel `x` see what pixel `x + offset * width` saw without
//! it).
use crate::math::sqrt;
use glam::{Vec2, Vec3};

/// Which image extent the field of view spans.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    /// Horizontal.
    X,
    /// Vertical.
    Y,
    /// Diagonal.
    Diagonal,
    /// The shorter image side.
    Smaller,
    /// The longer image side.
    Larger,
}

/// A pinhole projection: the frustum of a film of a given aspect ratio.
#[derive(Clone, Debug)]
pub struct Perspective {
    tan_x: f32,
    tan_y: f32,
    /// Principal point offset, in units of the film's width and height.
    offset: Vec2,
    /// Distance to the near clip plane (along the view axis).
    pub near: f32,
    /// Distance to the far clip plane (along the view axis).
    pub far: f32,
}

impl Perspective {
    /// The projection of a `width` x `height` film with field of view `fov_deg` along `axis`.
    pub fn new(width: u32, height: u32, fov_deg: f32, axis: FovAxis, near: f32, far: f32) -> Self {
        let (w, h) = (width as f32, height as f32);
        let t = libm::tanf(0.5 * fov_deg.to_radians());
        let axis = match axis {
            FovAxis::Smaller => {
                if w > h {
                    FovAxis::Y
                } else {
                    FovAxis::X
                }
            }
            FovAxis::Larger => {
                if w > h {
                    FovAxis::X
                } else {
                    FovAxis::Y
                }
            }
            a => a,
        };
        let tan_x = match axis {
            FovAxis::Y => t * w / h,
            FovAxis::Diagonal => t * w / sqrt(w * w + h * h),
            _ => t,
        };
        Perspective {
            tan_x,
            tan_y: tan_x * h / w,
            offset: Vec2::ZERO,
            near,
            far,
        }
    }

    /// Half the image's width and height at depth 1 (the tangents of the half fields of view).
    pub fn half_extent(&self) -> Vec2 {
        Vec2::new(self.tan_x, self.tan_y)
    }

    /// The same projection with its principal point moved by `offset` (Mitsuba 3's
    /// `principal_point_offset_x`/`_y`: fractions of the film's width and height).
    pub fn with_principal_point_offset(self, offset: Vec2) -> Self {
        Perspective { offset, ..self }
    }

    /// The point at depth 1 on the ray through film position `pos` of a `width` x `height`
    /// film (pixels, continuous; `(0,0)` is the top-left corner), in camera space.
    #[inline]
    pub(crate) fn image_point(&self, pos: Vec2, width: u32, height: u32) -> Vec3 {
        // Subtracting a zero offset is exact: without one, the directions are bit for bit those
        // of the plain pinhole.
        let x = (1.0 - 2.0 * pos.x / width as f32 - 2.0 * self.offset.x) * self.tan_x;
        let y = (1.0 - 2.0 * pos.y / height as f32 - 2.0 * self.offset.y) * self.tan_y;
        Vec3::new(x, y, 1.0)
    }
}

//! Pinhole perspective camera with Mitsuba 3's conventions.
//!
//! Scene parameters (`<sensor type="perspective">`): `fov` (float, degrees, required unless
//! `focal_length`), `fov_axis` (string x|y|diagonal|smaller|larger, default x), `to_world`
//! (transform, usually a lookat; the camera looks along local +z with +y up and local +x to the
//! image's left), `near_clip` (float, default 0.01), `far_clip` (float, default 10000). The film
//! (`width`, `height`) and filter live in `<film>`; Nori puts width/height on the camera.
use crate::math::{sqrt, Norm, Ray, Transform};
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

/// A perspective camera producing rays through continuous film positions.
#[derive(Clone, Debug)]
pub struct Perspective {
    /// Camera to world (rigid part used; scale is ignored).
    pub to_world: Transform,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    tan_x: f32,
    tan_y: f32,
    near: f32,
    far: f32,
}

impl Perspective {
    /// A camera with field of view `fov_deg` along `axis`.
    pub fn new(
        to_world: Transform,
        width: u32,
        height: u32,
        fov_deg: f32,
        axis: FovAxis,
        near: f32,
        far: f32,
    ) -> Self {
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
            to_world,
            width,
            height,
            tan_x,
            tan_y: tan_x * h / w,
            near,
            far,
        }
    }

    /// The ray through film position `pos` (pixels, continuous; `(0,0)` is the top-left corner).
    #[inline]
    pub fn generate_ray(&self, pos: Vec2) -> Ray {
        let x = (1.0 - 2.0 * pos.x / self.width as f32) * self.tan_x;
        let y = (1.0 - 2.0 * pos.y / self.height as f32) * self.tan_y;
        let local = Vec3::new(x, y, 1.0);
        // Distance along the unit direction to the clip planes z = near and z = far.
        let len = local.norm();
        let d = self.to_world.vector(local / len).unit();
        let o = self.to_world.point(Vec3::ZERO);
        let (near_t, far_t) = (self.near * len, self.far * len);
        Ray {
            o: o + d * near_t,
            d,
            t_max: far_t - near_t,
        }
    }
}

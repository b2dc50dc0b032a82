//! A ray with a parametric extent `[0, t_max)`.
use glam::Vec3;

/// A ray `o + t d` for `t` in `[0, t_max)`. `d` need not be normalized (shadow rays use the
/// unnormalized segment with `t_max` just below 1).
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    /// Origin (already offset off the surface it leaves).
    pub o: Vec3,
    /// Direction.
    pub d: Vec3,
    /// Exclusive upper bound of the parameter.
    pub t_max: f32,
}

impl Ray {
    /// A ray of unbounded extent.
    pub fn new(o: Vec3, d: Vec3) -> Self {
        Ray {
            o,
            d,
            t_max: f32::INFINITY,
        }
    }
    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}

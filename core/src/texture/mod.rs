//! Textures: spatially varying parameters looked up by surface `uv`. A closed enum; constant
//! values are the common case and cost one branch.
//!
//! Scalar lookups ([`Texture::eval_1`]) follow Mitsuba 3: the mean of the channels for a
//! constant, the luminance for a bitmap.
mod bitmap;
mod checkerboard;
mod lookup;
mod to_uv;

pub use bitmap::{Bitmap, FilterType, WrapMode};
pub use checkerboard::Checkerboard;
pub use lookup::Lookup;
pub use to_uv::UvTransform;

use crate::Color;
use glam::Vec2;

/// A colour (or scalar, stored as grey) that may vary over a surface.
#[derive(Clone, Debug)]
pub enum Texture {
    /// The same value everywhere.
    Constant(Color),
    /// An image (`bitmap`).
    Bitmap(Bitmap),
    /// A two-colour checkerboard (`checkerboard`).
    Checkerboard(Checkerboard<Texture>),
}

impl Texture {
    /// The image this texture reads, if it is one.
    pub fn bitmap(&self) -> Option<&Bitmap> {
        match self {
            Texture::Bitmap(b) => Some(b),
            _ => None,
        }
    }

    /// A constant grey value.
    pub fn constant(v: f32) -> Self {
        Texture::Constant(Color::splat(v))
    }
    /// The value at `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Color {
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.eval(uv),
            Texture::Checkerboard(c) => c.eval(uv),
        }
    }
    /// A scalar at `uv`, for weights and opacities: the mean of the channels of a constant (as
    /// Mitsuba 3's `rgb` does), the luminance of a bitmap (as Mitsuba 3's `bitmap` does).
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        match self {
            Texture::Constant(c) => (c.x + c.y + c.z) * (1.0 / 3.0),
            Texture::Bitmap(b) => b.eval_1(uv),
            Texture::Checkerboard(c) => c.eval_1(uv),
        }
    }
    /// The gradient of [`Texture::eval_1`] with respect to `(u, v)` (what `bumpmap` reads):
    /// zero for a constant, the bilinear lookup's for a bitmap ([`Bitmap::eval_1_grad`]), and
    /// zero for a checkerboard, which is constant almost everywhere. Mitsuba 3.9.1 implements
    /// it for bitmaps only; the scene loader refuses a checkerboard where a gradient is read.
    #[inline]
    pub fn eval_1_grad(&self, uv: Vec2) -> Vec2 {
        match self {
            Texture::Bitmap(b) => b.eval_1_grad(uv),
            Texture::Constant(_) | Texture::Checkerboard(_) => Vec2::ZERO,
        }
    }
    /// The mean colour over one period of the texture (of the image's pixels, of the two
    /// checkerboard colours' means): a power estimate for lights, not a lookup.
    pub(crate) fn mean_value(&self) -> Color {
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.mean_value(),
            Texture::Checkerboard(c) => (c.color0.mean_value() + c.color1.mean_value()) * 0.5,
        }
    }
    /// The largest channel value anywhere on the surface (an upper bound).
    pub fn max_value(&self) -> f32 {
        match self {
            Texture::Constant(c) => c.max_element(),
            Texture::Bitmap(b) => b.max_value(),
            Texture::Checkerboard(c) => c.max_value(),
        }
    }
}

impl Lookup for Texture {
    #[inline]
    fn eval(&self, uv: Vec2) -> Color {
        Texture::eval(self, uv)
    }
    #[inline]
    fn eval_1(&self, uv: Vec2) -> f32 {
        Texture::eval_1(self, uv)
    }
    fn max_value(&self) -> f32 {
        Texture::max_value(self)
    }
}

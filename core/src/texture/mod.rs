//! Textures: spatially varying parameters looked up at a shading point (its `uv`, and for
//! `mesh_attribute` the mesh triangle hit). A closed enum; constant values are the common case
//! and cost one branch. Lookups take anything that converts to a
//! [`ShadingPoint`], so callers that know only `uv` pass a `Vec2`.
//!
//! Scalar lookups ([`Texture::eval_1`]) follow Mitsuba 3: the mean of the channels for a
//! constant, the luminance for a bitmap.
mod bitmap;
mod checkerboard;
mod lookup;
mod mesh_attribute;
mod texels;
mod to_uv;

pub use bitmap::{Bitmap, FilterType, WrapMode};
pub use checkerboard::Checkerboard;
pub use lookup::Lookup;
pub use mesh_attribute::MeshAttributeTexture;
pub use texels::{CodeTable, Texels};
pub use to_uv::UvTransform;

use crate::geometry::ShadingPoint;
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
    /// A mesh's per-vertex or per-face values (`mesh_attribute`).
    MeshAttribute(MeshAttributeTexture),
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
    /// Whether this is a `mesh_attribute` texture (which reads the triangle hit).
    pub fn reads_mesh(&self) -> bool {
        matches!(self, Texture::MeshAttribute(_))
    }
    /// The value at `at`. An image's lookup is remembered in `at`'s memo, if it has one, and
    /// read from there when repeated (the same bits).
    #[inline(always)]
    pub fn eval<'a>(&self, at: impl Into<ShadingPoint<'a>>) -> Color {
        let at = at.into();
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.eval_remembered(at.uv, at.memo),
            Texture::Checkerboard(c) => c.eval(at.uv),
            Texture::MeshAttribute(m) => m.eval(at),
        }
    }
    /// A scalar at `at`, for weights and opacities: the mean of the channels of a constant (as
    /// Mitsuba 3's `rgb` does), the luminance of a bitmap (as Mitsuba 3's `bitmap` does).
    #[inline]
    pub fn eval_1<'a>(&self, at: impl Into<ShadingPoint<'a>>) -> f32 {
        let at = at.into();
        match self {
            Texture::Constant(c) => (c.x + c.y + c.z) * (1.0 / 3.0),
            Texture::Bitmap(b) => Bitmap::luminance(b.eval_remembered(at.uv, at.memo)),
            Texture::Checkerboard(c) => c.eval_1(at.uv),
            Texture::MeshAttribute(m) => m.eval_1(at),
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
            Texture::Constant(_) | Texture::Checkerboard(_) | Texture::MeshAttribute(_) => {
                Vec2::ZERO
            }
        }
    }
    /// The mean colour over one period of the texture (of the image's pixels, of the two
    /// checkerboard colours' means): a power estimate for lights, not a lookup.
    pub(crate) fn mean_value(&self) -> Color {
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.mean_value(),
            Texture::Checkerboard(c) => (c.color0.mean_value() + c.color1.mean_value()) * 0.5,
            Texture::MeshAttribute(m) => Color::splat(m.scale),
        }
    }
    /// The largest channel value anywhere on the surface (an upper bound).
    pub fn max_value(&self) -> f32 {
        match self {
            Texture::Constant(c) => c.max_element(),
            Texture::Bitmap(b) => b.max_value(),
            Texture::Checkerboard(c) => c.max_value(),
            Texture::MeshAttribute(_) => f32::INFINITY,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::LookupMemo;
    use alloc::vec;

    /// Through a shading point with a memo, an image is read once: the first lookup gives the
    /// image's value, a repeat gives the remembered one (shown by asking the repeat at other
    /// coordinates, which a shading point never does), scalar lookups included. The control,
    /// the same lookups without a memo, reads the image each time.
    #[test]
    fn a_memo_reads_each_image_once() {
        let pixels = vec![Color::new(0.2, 0.4, 0.6), Color::new(1.0, 0.5, 0.0)];
        let image = Bitmap::new(
            2,
            1,
            pixels,
            FilterType::Nearest,
            WrapMode::Repeat,
            UvTransform::default(),
        )
        .unwrap();
        let t = Texture::Bitmap(image.clone());
        let (left, right) = (Vec2::new(0.25, 0.5), Vec2::new(0.75, 0.5));
        let memo = LookupMemo::default();
        let with = |uv| ShadingPoint {
            uv,
            partials: None,
            memo: Some(&memo),
        };
        assert_eq!(t.eval(with(left)), image.eval(left));
        assert_eq!(t.eval(with(right)), image.eval(left));
        assert_eq!(t.eval_1(with(right)), image.eval_1(left));
        assert_ne!(t.eval(right), image.eval(left));
        assert_eq!(t.eval(right), image.eval(right));
        assert_eq!(t.eval_1(right), image.eval_1(right));
    }
}

//! Textures: spatially varying parameters looked up by surface `uv`. A closed enum; constant
//! values are the common case and cost one branch.
use crate::Color;
use glam::Vec2;

/// A colour (or scalar, stored as grey) that may vary over a surface.
#[derive(Clone, Debug)]
pub enum Texture {
    /// The same value everywhere.
    Constant(Color),
}

impl Texture {
    /// A constant grey value.
    pub fn constant(v: f32) -> Self {
        Texture::Constant(Color::splat(v))
    }
    /// The value at `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Color {
        match self {
            Texture::Constant(c) => {
                let _ = uv;
                *c
            }
        }
    }
    /// A scalar at `uv` (the mean of the channels), for weights and opacities.
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        let c = self.eval(uv);
        (c.x + c.y + c.z) * (1.0 / 3.0)
    }
    /// The largest channel value anywhere on the surface (an upper bound).
    pub fn max_value(&self) -> f32 {
        match self {
            Texture::Constant(c) => c.max_element(),
        }
    }
}

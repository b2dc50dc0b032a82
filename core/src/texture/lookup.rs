//! What a texture that holds other textures asks of them: the lookups, as a trait, so that such
//! a texture (the checkerboard) is written over any texture type and its file need not know the
//! `Texture` enum that holds it (the enum implements the trait by dispatching on its variants).
use crate::Color;
use glam::Vec2;

/// A texture's lookups.
pub trait Lookup {
    /// The colour at `uv`.
    fn eval(&self, uv: Vec2) -> Color;
    /// The scalar value at `uv`.
    fn eval_1(&self, uv: Vec2) -> f32;
    /// An upper bound of the scalar values.
    fn max_value(&self) -> f32;
}

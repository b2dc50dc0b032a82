//! A procedural two-colour checkerboard (`checkerboard`), as Mitsuba 3 draws it.
//!
//! Scene parameters (`<texture type="checkerboard">`, read by the driver): `color0` (rgb or
//! texture, default 0.4), `color1` (rgb or texture, default 0.2), `to_uv` (transform, see
//! [`UvTransform`]).
//!
//! After `to_uv`, with `(s, t)` the fractional parts of `(u, v)`: `color0` where `s > 1/2` and
//! `t > 1/2` agree (both or neither), `color1` elsewhere; one period covers the unit square in
//! 2 x 2 patches, `color0` at the patch containing `uv = 0`. The scalar lookup
//! ([`Checkerboard::eval_1`]) picks the same patch; Mitsuba 3.9.1's `eval_1` picks the opposite
//! one (measured; its colour lookup agrees with ours), which Tessera does not copy.
use super::lookup::Lookup;
use super::to_uv::UvTransform;
use crate::Color;
use alloc::boxed::Box;
use glam::Vec2;

/// Two textures in a checkerboard pattern; `T` is the texture type of the patches (the
/// `Texture` enum, which holds this pattern as one of its variants).
#[derive(Clone, Debug)]
pub struct Checkerboard<T> {
    /// The patches containing `uv = (0, 0)` and `(1/2 + e, 1/2 + e)`.
    pub color0: Box<T>,
    /// The other patches.
    pub color1: Box<T>,
    /// Map applied to `uv` first.
    pub to_uv: UvTransform,
}

impl<T: Lookup> Checkerboard<T> {
    fn pick(&self, uv: Vec2) -> &T {
        let p = self.to_uv.apply(uv);
        let s = p.x - libm::floorf(p.x) > 0.5;
        let t = p.y - libm::floorf(p.y) > 0.5;
        if s == t {
            &self.color0
        } else {
            &self.color1
        }
    }

    /// The colour at `uv` (the nested textures are looked up at the original `uv`).
    pub fn eval(&self, uv: Vec2) -> Color {
        self.pick(uv).eval(uv)
    }

    /// The scalar value at `uv`: the chosen patch's own scalar lookup.
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        self.pick(uv).eval_1(uv)
    }

    /// The larger of the two patches' maxima.
    pub fn max_value(&self) -> f32 {
        self.color0.max_value().max(self.color1.max_value())
    }
}

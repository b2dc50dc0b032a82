//! The `to_uv` parameter of textures: a 2-D affine map applied to the surface `uv` before the
//! lookup.
//!
//! Scene parameter (`<transform name="to_uv">`, default identity): Mitsuba 3 reads a 4x4
//! transform and keeps rows and columns 0, 1 and 3, so `<scale x= y=>`, `<translate x= y=>`
//! and rotations about z act on `(u, v)` as they would on `(x, y)`; z parts are ignored.
use glam::Vec2;

/// `uv' = (a u + b v + c, d u + e v + f)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    /// Row for `u'`: `[a, b, c]`.
    pub row_u: [f32; 3],
    /// Row for `v'`: `[d, e, f]`.
    pub row_v: [f32; 3],
}

impl UvTransform {
    /// The identity map.
    pub const IDENTITY: UvTransform = UvTransform {
        row_u: [1.0, 0.0, 0.0],
        row_v: [0.0, 1.0, 0.0],
    };

    /// Applies the map.
    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let [a, b, c] = self.row_u;
        let [d, e, f] = self.row_v;
        Vec2::new(a * uv.x + b * uv.y + c, d * uv.x + e * uv.y + f)
    }
}

impl Default for UvTransform {
    fn default() -> Self {
        UvTransform::IDENTITY
    }
}

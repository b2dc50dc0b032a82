//! What the path loop asks of a BSDF at every vertex before using it (which random inputs its
//! sampling reads, whether emitter sampling can help), answered once per BSDF when the scene is
//! built (`Scene::bsdf_traits`) instead of by two dispatches per bounce. The answers come from
//! the enum's dispatch (`BsdfTraits::of`, with the enum), so this file does not depend on it.
use crate::sampling::Sampler;
use glam::Vec2;

/// The per-vertex questions of `Bsdf::sample_inputs` and `Bsdf::has_smooth`, answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BsdfTraits {
    /// `Bsdf::sample` reads `u1` (it chooses among components).
    pub uses_u1: bool,
    /// `Bsdf::sample` reads `u2`.
    pub uses_u2: bool,
    /// Some component is smooth (non-delta): emitter sampling can contribute.
    pub has_smooth: bool,
    /// `Bsdf::is_lambertian`: path reuse may share the light it reflects.
    pub lambertian: bool,
    /// Some part of the model reads the shading point's partials (`bumpmap`).
    pub reads_geometry: bool,
    /// Some texture of the model is an image (`Bsdf::reads_images`): its vertices keep a
    /// `LookupMemo`.
    pub reads_images: bool,
    /// Some part of the model reads the surface's texture coordinates (`Bsdf::reads_uv`).
    pub reads_uv: bool,
}

impl BsdfTraits {
    /// Draws `(u1, u2)` for `Bsdf::sample` as `Bsdf::draw_sample_inputs` does: the inputs
    /// the BSDF ignores are skipped, not drawn, and given as 0.5.
    #[inline(always)]
    pub fn draw_sample_inputs<S: Sampler>(self, sampler: &mut S) -> (f32, Vec2) {
        draw_inputs(self.uses_u1, self.uses_u2, sampler)
    }
}

/// Draws `u1` (when `uses_u1`) and `u2` (when `uses_u2`) from the sampler's next three
/// dimensions, skipping the others and giving them as 0.5.
#[inline(always)]
pub(super) fn draw_inputs<S: Sampler>(
    uses_u1: bool,
    uses_u2: bool,
    sampler: &mut S,
) -> (f32, Vec2) {
    let u1 = if uses_u1 {
        sampler.next_1d()
    } else {
        sampler.skip_1d();
        0.5
    };
    let u2 = if uses_u2 {
        sampler.next_2d()
    } else {
        sampler.skip_1d();
        sampler.skip_1d();
        Vec2::splat(0.5)
    };
    (u1, u2)
}

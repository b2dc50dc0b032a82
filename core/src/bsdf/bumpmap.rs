//! Bump mapping (`bumpmap`, Mitsuba 3): a scalar height texture tilts the shading frame and the
//! nested model is evaluated around the tilted normal.
//!
//! With `h(u, v) = scale * texture(u, v)` (the texture's luminance; its uv gradient from
//! [`Texture::eval_1_grad`]), the surface's partials `dp/du`, `dp/dv` (in the local shading
//! frame, from the [`ShadingPoint`]) have their normal components replaced by `dh/du` and
//! `dh/dv`; the tilted normal is their normalised cross product, turned to the side of the
//! geometric normal. The flip of normals that face away from `wi`, the frame around the normal,
//! the side test and the shadowing term are those of [`super::perturbed`].
//!
//! The tilted frame's first tangent is `dp/du` projected onto the plane normal to the tilted
//! normal. Mitsuba 3.9.1 projects the world-space `dp/du` with the local normal there (a mix of
//! frames); here both are local, which is what it computes wherever the shading frame is the
//! world's axes (as in its per-BSDF tables, `scripts/mitsuba_bsdf_eval.py`). The normal, and
//! so every isotropic nested model's values, are the same in any frame; only an anisotropic
//! nested model could tell. A zero cross product (degenerate partials) leaves the frame
//! unperturbed.
use super::model::Model;
use super::perturbed::{PerturbOptions, Tilted};
use super::sample::BsdfSample;
use crate::geometry::{Partials, ShadingPoint};
use crate::texture::Texture;
use crate::Color;
use alloc::boxed::Box;
use glam::{Vec2, Vec3};

/// A model seen through a height field (`bumpmap`).
#[derive(Clone, Debug)]
pub struct BumpMap<B> {
    /// The height texture (its luminance), usually a bitmap read with `raw`.
    pub height: Texture,
    /// Multiplies the height (`scale`, default 1).
    pub scale: f32,
    /// The model evaluated in the perturbed frame.
    pub nested: Box<B>,
    /// How the perturbed frame is built and weighted.
    pub options: PerturbOptions,
}

/// The tilted normal (not normalised) in the local frame for height gradient `grad` (per unit
/// `u` and `v`) for partials `g`.
#[inline]
pub(crate) fn bumped_normal(g: &Partials, grad: Vec2) -> Vec3 {
    let du = Vec3::new(g.dp_du.x, g.dp_du.y, grad.x);
    let dv = Vec3::new(g.dp_dv.x, g.dp_dv.y, grad.y);
    let n = du.cross(dv);
    if n.dot(g.ng) < 0.0 {
        -n
    } else {
        n
    }
}

impl<B: Model> BumpMap<B> {
    #[inline]
    fn tilted(&self, wi: Vec3, at: &ShadingPoint) -> Tilted {
        let grad = self.height.eval_1_grad(at.uv) * self.scale;
        let g = at.partials_or_flat();
        Tilted::with_tangent(bumped_normal(&g, grad), g.dp_du, wi, self.options)
    }
    /// The nested value in the perturbed frame.
    pub fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        self.tilted(wi, &at).eval(&*self.nested, wi, wo, at)
    }
    /// The nested density in the perturbed frame.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        self.tilted(wi, &at).pdf(&*self.nested, wi, wo, at)
    }
    /// Samples the nested model in the perturbed frame.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        self.tilted(wi, &at).sample(&*self.nested, wi, u1, u2, at)
    }
    /// Whether the nested model has a smooth component.
    pub fn has_smooth(&self) -> bool {
        self.nested.has_smooth()
    }
    /// Whether the nested model has a delta component.
    pub fn has_delta(&self) -> bool {
        self.nested.has_delta()
    }
}

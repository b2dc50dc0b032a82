//! The scene's ray queries: the closest surface interaction (its texture coordinates computed
//! only where the surface's BSDF or emitter reads them, unless asked for), the closest hit
//! alone, occlusion, and one primitive's test.
use super::Scene;
use crate::accel::level::NOT_A_TRIANGLE;
use crate::accel::tri_block::Ray4;
use crate::accel::AnyLeaves;
use crate::geometry::{Hit, Interaction, Prim, TriRay};
use crate::math::Ray;
use core::cell::Cell;
use glam::{Vec2, Vec3};

impl Scene {
    /// Intersection of the ray (within `(0, t_max)`) with primitive `i` alone: `(t, uv)`. The
    /// scalar reference the block tests agree with (it reads the shape, not the blocks).
    pub fn intersect_prim(
        &self,
        i: usize,
        ray: &Ray,
        tri: &TriRay,
        t_max: f32,
    ) -> Option<(f32, Vec2)> {
        if let Prim::Instance { .. } = self.prims[i] {
            return self.other_prim::<false>(i, ray, &NOT_A_TRIANGLE, t_max, &Cell::default());
        }
        let v = self.triangle(i).unwrap_or(NOT_A_TRIANGLE);
        self.prims[i].intersect(ray, tri, &v, t_max, &self.disks, &self.shapes)
    }

    /// The closest hit along the ray, if any.
    pub fn intersect_hit(&self, ray: &Ray) -> Option<Hit> {
        self.closest(ray, &Cell::default())
    }

    /// The closest surface interaction along the ray, if any: what shading reads. Its `uv` is
    /// zero on a sphere whose BSDF and emitter read no texture coordinates (see
    /// [`Scene::reads_uv`]); [`Scene::intersect_full`] computes them everywhere.
    pub fn intersect(&self, ray: &Ray) -> Option<Interaction> {
        self.interaction_along::<false>(ray)
    }

    /// [`Scene::intersect`] with the texture coordinates computed on every shape (for outputs
    /// that show them).
    pub fn intersect_full(&self, ray: &Ray) -> Option<Interaction> {
        self.interaction_along::<true>(ray)
    }

    /// Whether hits on shape `shape` compute their texture coordinates in
    /// [`Scene::intersect`]: every shape but a sphere whose BSDF (nested models and bump maps
    /// included) and area emitter read none.
    #[inline]
    pub fn reads_uv(&self, shape: u32) -> bool {
        self.uv_read[shape as usize]
    }

    #[inline(always)]
    fn interaction_along<const FULL: bool>(&self, ray: &Ray) -> Option<Interaction> {
        let inner = Cell::default();
        let hit = self.closest(ray, &inner)?;
        let prim = &self.prims[hit.prim as usize];
        if let Prim::Instance { instance } = prim {
            let inst = &self.instances[*instance as usize];
            let g = &self.groups[inst.group as usize];
            let ih = inner.get();
            let gp = &g.prims[ih.prim as usize];
            let oray = inst.to_object(ray);
            let ohit = Hit {
                t: hit.t,
                prim: ih.prim,
                uv: ih.uv,
            };
            let shape = gp.shape();
            let uv = FULL || self.reads_uv(shape);
            let it = self.shapes[shape as usize].interaction(&ohit, gp, &oray, &self.disks, uv);
            return Some(inst.interaction_to_world(&it, ray));
        }
        let shape = prim.shape();
        let uv = FULL || self.reads_uv(shape);
        Some(self.shapes[shape as usize].interaction(&hit, prim, ray, &self.disks, uv))
    }

    /// Whether anything blocks the ray within its extent (any hit, early exit).
    pub fn occluded(&self, ray: &Ray) -> bool {
        let r4 = Ray4::from_ray(ray);
        let inner = Cell::default();
        let mut leaves = AnyLeaves {
            blocks: &self.blocks,
            ray: &r4,
            hit: false,
            other: |i: usize, v: &[Vec3; 3], t_max: f32| {
                self.other_prim::<true>(i, ray, v, t_max, &inner)
            },
        };
        self.bvh.cast::<true>(ray, &mut leaves);
        leaves.hit
    }
}

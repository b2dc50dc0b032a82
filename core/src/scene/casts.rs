//! The scene's casts below the hierarchy walk: the closest hit, the leaf tests shared with the
//! counted casts, and primitives that are not triangles of the blocks (spheres and disks
//! directly, an instance through its group's own hierarchy with the ray in object space).
use super::Scene;
use crate::accel::tri_block::Ray4;
use crate::accel::{AnyLeaves, ClosestLeaves};
use crate::geometry::{Hit, Prim, TriRay};
use crate::math::Ray;
use core::cell::Cell;
use glam::{Vec2, Vec3};

impl Scene {
    /// The closest hit along the ray; where it is on an instance, `inner` says where in its
    /// group.
    #[inline(always)]
    pub(super) fn closest(&self, ray: &Ray, inner: &Cell<InnerHit>) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let r4 = Ray4::from_ray(ray);
        self.bvh.cast::<false>(
            ray,
            ClosestLeaves {
                blocks: &self.blocks,
                ray: &r4,
                best: &mut best,
                other: |i: usize, v: &[Vec3; 3], t_max: f32| {
                    self.other_prim::<false>(i, ray, v, t_max, inner)
                },
            },
        );
        best
    }

    /// Tests the primitives `prims` of a leaf for a hit closer than `t_max`, updating `best`;
    /// returns the new `t_max`. Shared by the ordinary and the counted casts.
    #[inline(always)]
    pub(crate) fn leaf_closest(
        &self,
        ray: &Ray,
        r4: &Ray4,
        prims: core::ops::Range<usize>,
        t_max: f32,
        best: &mut Option<Hit>,
    ) -> f32 {
        let inner = Cell::default();
        self.blocks
            .closest(prims.start, prims.len(), r4, t_max, best, |i, v, t_max| {
                self.other_prim::<false>(i, ray, v, t_max, &inner)
            })
    }

    /// Whether any primitive of `prims` blocks the ray before `t_max` (ordinary and counted
    /// casts).
    #[inline(always)]
    pub(crate) fn leaf_any(
        &self,
        ray: &Ray,
        r4: &Ray4,
        prims: core::ops::Range<usize>,
        t_max: f32,
    ) -> bool {
        let inner = Cell::default();
        self.blocks
            .any(prims.start, prims.len(), r4, t_max, |i, v, t_max| {
                self.other_prim::<true>(i, ray, v, t_max, &inner)
            })
    }

    /// The test of primitive `i`, which is not a triangle (the leaves' `other`; `v` is its NaN
    /// corners). An instance is tested through its group's hierarchy: for the closest hit
    /// (`ANY` false) `inner` then records where in the group the hit is, for any hit the walk
    /// stops at the first.
    #[inline(always)]
    pub(super) fn other_prim<const ANY: bool>(
        &self,
        i: usize,
        ray: &Ray,
        v: &[Vec3; 3],
        t_max: f32,
        inner: &Cell<InnerHit>,
    ) -> Option<(f32, Vec2)> {
        match &self.prims[i] {
            Prim::Instance { instance } => self.instance_hit::<ANY>(*instance, ray, t_max, inner),
            pr => self.plain_prim(pr, ray, v, t_max),
        }
    }

    /// The test of a primitive that is neither a triangle of the blocks nor an instance.
    #[inline(always)]
    fn plain_prim(&self, pr: &Prim, ray: &Ray, v: &[Vec3; 3], t_max: f32) -> Option<(f32, Vec2)> {
        match pr {
            Prim::Sphere { sphere, .. } => sphere.intersect(ray, t_max).map(|t| (t, Vec2::ZERO)),
            Prim::Disk { disk, .. } => self.disks[*disk as usize].intersect(ray, t_max),
            // Not reached from the blocks (a triangle's lane is tested there); as the scalar test.
            pr => pr.intersect(ray, &TriRay::new(ray), v, t_max, &self.disks, &self.shapes),
        }
    }

    /// A ray against instance `instance` within `(0, t_max)`: the group's hierarchy walked with
    /// the ray in object space (where `t` measures the same points).
    #[inline(never)]
    fn instance_hit<const ANY: bool>(
        &self,
        instance: u32,
        ray: &Ray,
        t_max: f32,
        inner: &Cell<InnerHit>,
    ) -> Option<(f32, Vec2)> {
        let inst = &self.instances[instance as usize];
        let g = &self.groups[inst.group as usize];
        let oray = inst.to_object(&Ray { t_max, ..*ray });
        let r4 = Ray4::from_ray(&oray);
        let other = |j: usize, v: &[Vec3; 3], t: f32| self.plain_prim(&g.prims[j], &oray, v, t);
        if ANY {
            let mut leaves = AnyLeaves {
                blocks: &g.blocks,
                ray: &r4,
                hit: false,
                other,
            };
            g.bvh.cast::<true>(&oray, &mut leaves);
            return leaves.hit.then_some((t_max, Vec2::ZERO));
        }
        let mut best: Option<Hit> = None;
        g.bvh.cast::<false>(
            &oray,
            ClosestLeaves {
                blocks: &g.blocks,
                ray: &r4,
                best: &mut best,
                other,
            },
        );
        let h = best?;
        inner.set(InnerHit {
            prim: h.prim,
            uv: h.uv,
        });
        Some((h.t, Vec2::ZERO))
    }
}

/// Where a closest hit on an instance landed inside its group: the group's primitive and its
/// uv (the top level's [`Hit`] names the instance).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct InnerHit {
    pub(super) prim: u32,
    pub(super) uv: Vec2,
}

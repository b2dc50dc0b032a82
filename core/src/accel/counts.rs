//! Counted ray casts: the work one closest-hit or any-hit query does (nodes visited, leaves
//! and triangle blocks tested), for statistics such as `--stats` and the benches. They return
//! exactly what [`Scene::intersect_hit`] and [`Scene::occluded`] return; the ordinary casts are
//! compiled without counters.
use super::tri_block::Ray4;
use crate::geometry::Hit;
use crate::math::Ray;
use crate::scene::Scene;

/// Work done by counted ray casts, summed over the rays counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraversalCounts {
    /// Rays cast.
    pub rays: u64,
    /// BVH nodes visited (each an eight-box test).
    pub nodes: u64,
    /// Leaves reached.
    pub leaves: u64,
    /// Four-triangle blocks in the leaves reached (an any-hit query may stop before the last).
    pub blocks: u64,
}

impl TraversalCounts {
    /// Adds another tally to this one.
    pub fn add(&mut self, o: &TraversalCounts) {
        self.rays += o.rays;
        self.nodes += o.nodes;
        self.leaves += o.leaves;
        self.blocks += o.blocks;
    }
}

impl Scene {
    /// [`Scene::intersect_hit`], counting its work into `c`.
    pub fn intersect_hit_counted(&self, ray: &Ray, c: &mut TraversalCounts) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let r4 = Ray4::from_ray(ray);
        let (mut leaves, mut blocks) = (0u64, 0u64);
        let leaf = |first: usize, count: usize, t_max: f32| {
            leaves += 1;
            blocks += count.div_ceil(4) as u64;
            self.leaf_closest(ray, &r4, first..first + count, t_max, &mut best)
        };
        self.bvh.traverse_closest_counted(ray, leaf, &mut c.nodes);
        c.rays += 1;
        c.leaves += leaves;
        c.blocks += blocks;
        best
    }

    /// [`Scene::occluded`], counting its work into `c`.
    pub fn occluded_counted(&self, ray: &Ray, c: &mut TraversalCounts) -> bool {
        let mut hit = false;
        let r4 = Ray4::from_ray(ray);
        let (mut leaves, mut blocks) = (0u64, 0u64);
        let leaf = |first: usize, count: usize, t_max: f32| {
            leaves += 1;
            blocks += count.div_ceil(4) as u64;
            hit = self.leaf_any(ray, &r4, first..first + count, t_max);
            hit
        };
        self.bvh.traverse_any_counted(ray, leaf, &mut c.nodes);
        c.rays += 1;
        c.leaves += leaves;
        c.blocks += blocks;
        hit
    }
}

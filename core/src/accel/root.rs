//! The traversal of an 8-wide hierarchy that is a single node (small scenes such as the Cornell
//! box, whose up to eight children are all leaves): one box test, then the leaves in the order
//! the general walk ([`Bvh8::cast`]) visits them, without its stack.
//!
//! Closest hit: leaves by entry distance, equal distances in lane order, each only while it is
//! entered within the closest hit so far; any hit: the lowest hit lane first, then the others
//! from the highest lane down, stopping at the first hit. These are the general walk's orders
//! (it pushes the children on a stack sorted by distance, or in lane order for any hit), so the
//! leaves see the same calls with the same `t_max` and the results are the same. No prefetching:
//! a one-node scene's leaves are a few kilobytes.
use super::slab::RayPre;
use super::slab_simd::Hit8;
use super::{Bvh8, Leaves};
use crate::math::Ray;

impl Bvh8 {
    /// Walks a hierarchy of exactly one node (see the module header); `nodes` counts the node
    /// when `COUNT`.
    #[inline(always)]
    pub(super) fn walk_root<const ANY: bool, const COUNT: bool, H: Hit8, L: Leaves>(
        &self,
        test: H,
        ray: &Ray,
        mut leaf: L,
        nodes: &mut u64,
    ) {
        debug_assert_eq!(self.nodes.len(), 1);
        let node = &self.nodes[0];
        if COUNT {
            *nodes += 1;
        }
        let pre = RayPre::new(ray);
        let mut t_max = ray.t_max;
        let (mask, t_near) = test.hit8(&node.boxes, &pre, t_max);
        let mut mask = mask & node.used;
        let visit = |leaf: &mut L, lane: usize, t_max: f32| {
            let (first, count) = (node.child[lane] as usize, usize::from(node.count[lane]));
            leaf.test(test, first, count, t_max)
        };
        if ANY {
            if mask == 0 {
                return;
            }
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            if visit(&mut leaf, lane, t_max).is_none() {
                return;
            }
            while mask != 0 {
                let lane = 31 - mask.leading_zeros() as usize;
                mask &= !(1 << lane);
                if visit(&mut leaf, lane, t_max).is_none() {
                    return;
                }
            }
            return;
        }
        while mask != 0 {
            // The nearest remaining leaf (the lowest lane among equals).
            let mut lane = mask.trailing_zeros() as usize;
            let mut m = mask & (mask - 1);
            while m != 0 {
                let l = m.trailing_zeros() as usize;
                m &= m - 1;
                if t_near[l] < t_near[lane] {
                    lane = l;
                }
            }
            // Entered beyond the closest hit so far: so are the rest.
            if t_near[lane] > t_max {
                return;
            }
            mask &= !(1 << lane);
            match visit(&mut leaf, lane, t_max) {
                Some(t) => t_max = t,
                None => return,
            }
        }
    }
}

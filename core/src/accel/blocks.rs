//! Leaves as blocks of four triangles: packing a wide BVH's leaves ([`Bvh4`], [`Bvh8`]) into
//! [`Tri4`] blocks, and the closest-hit and any-hit loops over one leaf.
//!
//! Each leaf's primitives (a range of the build order) fill `ceil(count / 4)` consecutive
//! blocks; the leaf then refers to its first block instead of its first primitive. A primitive
//! that is not a triangle (sphere, disk) takes a lane with NaN corners, which the four-lane test
//! hands back as a fallback lane, and the caller's own test decides it. The loops visit lanes in
//! primitive order and lower `t_max` as they go, exactly as a loop of scalar tests over the
//! leaf's primitives would, so they find the same primitive at the same distance.
use super::tri4::{test4, Ray4, Tri4};
use super::{Bvh4, Bvh8};
use crate::geometry::{Hit, TriRay};
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// A hierarchy whose leaves refer to ranges of primitives, which [`TriBlocks::build`] remaps.
pub trait LeafRanges {
    /// Replaces each leaf's first primitive by `f(first, count)`, visiting leaves in node order.
    fn map_leaves(&mut self, f: impl FnMut(usize, usize) -> u32);
}

impl LeafRanges for Bvh4 {
    fn map_leaves(&mut self, f: impl FnMut(usize, usize) -> u32) {
        Bvh4::map_leaves(self, f);
    }
}

impl LeafRanges for Bvh8 {
    fn map_leaves(&mut self, f: impl FnMut(usize, usize) -> u32) {
        Bvh8::map_leaves(self, f);
    }
}

/// The triangle blocks of all leaves.
#[derive(Clone, Debug, Default)]
pub struct TriBlocks {
    /// Blocks, each leaf's consecutive.
    pub blocks: Vec<Tri4>,
}

impl TriBlocks {
    /// Packs every leaf of `bvh` (whose leaves refer to ranges of `corners`, NaN corners for a
    /// primitive that is not a triangle) into blocks and makes the leaves refer to their first
    /// block.
    pub fn build(bvh: &mut impl LeafRanges, corners: &[[Vec3; 3]]) -> TriBlocks {
        let mut blocks = Vec::with_capacity(corners.len() / 3 + 1);
        bvh.map_leaves(|first, count| {
            let at = blocks.len() as u32;
            for start in (first..first + count).step_by(4) {
                let mut b = Tri4::EMPTY;
                b.first = start as u32;
                for (lane, c) in corners[start..(start + 4).min(first + count)]
                    .iter()
                    .enumerate()
                {
                    b.set(lane, c);
                }
                blocks.push(b);
            }
            at
        });
        // The capacity guess above is generous; keep only what the leaves use.
        blocks.shrink_to_fit();
        TriBlocks { blocks }
    }

    /// Bytes the blocks occupy (not counting spare vector capacity).
    pub fn memory_bytes(&self) -> usize {
        core::mem::size_of_val(self.blocks.as_slice())
    }

    /// The lanes of block `k` (0-based within a leaf of `count` primitives) that hold primitives.
    #[inline(always)]
    fn valid(k: usize, count: usize) -> u32 {
        let n = (count - 4 * k).min(4);
        (1u32 << n) - 1
    }

    /// Closest hit among the `count` primitives of the leaf whose blocks start at `first`,
    /// within `(0, t_max)`: updates `best` and returns the new `t_max`. `other(prim, corners, t_max)`
    /// intersects a primitive that is not a triangle (its lane's corners are NaN).
    #[inline(always)]
    pub fn closest(
        &self,
        first: usize,
        count: usize,
        ray: (&TriRay, &Ray4),
        mut t_max: f32,
        best: &mut Option<Hit>,
        mut other: impl FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
    ) -> f32 {
        let (tri, r4) = ray;
        for k in 0..count.div_ceil(4) {
            let blk = &self.blocks[first + k];
            let lanes = test4(blk, r4, t_max);
            let valid = Self::valid(k, count);
            let mut m = (lanes.hit | lanes.fallback) & valid;
            while m != 0 {
                let lane = m.trailing_zeros() as usize;
                m &= m - 1;
                let prim = blk.first as usize + lane;
                let found = if lanes.fallback & (1 << lane) != 0 {
                    fallback(blk, lane, prim, tri, t_max, &mut other)
                } else if lanes.accepts(lane, t_max) {
                    Some((lanes.t[lane], Vec2::new(lanes.b[1][lane], lanes.b[2][lane])))
                } else {
                    None
                };
                if let Some((t, uv)) = found {
                    t_max = t;
                    *best = Some(Hit {
                        t,
                        prim: prim as u32,
                        uv,
                    });
                }
            }
        }
        t_max
    }

    /// Whether any of the `count` primitives of the leaf whose blocks start at `first` is hit
    /// within `(0, t_max)`; `other` as for [`TriBlocks::closest`].
    #[inline(always)]
    pub fn any(
        &self,
        first: usize,
        count: usize,
        ray: (&TriRay, &Ray4),
        t_max: f32,
        mut other: impl FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
    ) -> bool {
        let (tri, r4) = ray;
        for k in 0..count.div_ceil(4) {
            let blk = &self.blocks[first + k];
            let lanes = test4(blk, r4, t_max);
            let valid = Self::valid(k, count);
            if lanes.hit & valid != 0 {
                return true;
            }
            let mut m = lanes.fallback & valid;
            while m != 0 {
                let lane = m.trailing_zeros() as usize;
                m &= m - 1;
                let prim = blk.first as usize + lane;
                if fallback(blk, lane, prim, tri, t_max, &mut other).is_some() {
                    return true;
                }
            }
        }
        false
    }
}

/// The scalar test of a lane the four-lane test left undecided.
#[inline(never)]
fn fallback(
    blk: &Tri4,
    lane: usize,
    prim: usize,
    tri: &TriRay,
    t_max: f32,
    other: &mut impl FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
) -> Option<(f32, Vec2)> {
    let v = blk.corners(lane);
    if v[0].x.is_nan() {
        return other(prim, &v, t_max);
    }
    let [p0, p1, p2] = v;
    tri.intersect(t_max, p0, p1, p2)
        .map(|(t, _, b1, b2)| (t, Vec2::new(b1, b2)))
}

//! Leaves as blocks of four triangles: packing a wide BVH's leaves ([`Bvh8`]) into [`Tri4`]
//! blocks, and the closest-hit and any-hit loops over one leaf.
//!
//! Each leaf's primitives (a range of the build order) fill `ceil(count / 4)` consecutive
//! blocks; the leaf then refers to its first block instead of its first primitive. A primitive
//! that is not a triangle (sphere, disk) takes a lane with NaN corners; the loops find those
//! lanes with one compare per block ([`Tri4::nan_lanes`]) and call the caller's own test for
//! them directly (a block holding no triangle skips the triangle test). The closest-hit loop
//! visits lanes in primitive order and lowers `t_max` as it goes, exactly as a loop of scalar
//! tests over the leaf's primitives would, so it finds the same primitive at the same distance.
use super::leaves::Leaves;
use super::slab_simd::{prefetch_in, Hit8, Portable};
use super::tri_block::{Ray4, Tri4};
use super::Bvh8;
use crate::geometry::Hit;
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// A hierarchy whose leaves refer to ranges of primitives, which [`TriBlocks::build`] remaps.
pub trait LeafRanges {
    /// Replaces each leaf's first primitive by `f(first, count)`, visiting leaves in node order.
    fn map_leaves(&mut self, f: impl FnMut(usize, usize) -> u32);
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
    /// Whether some lane holds a primitive that is not a triangle (else the loops skip looking
    /// for such lanes).
    others: bool,
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
        let others = corners.iter().any(|c| c[0].x.is_nan());
        TriBlocks { blocks, others }
    }

    /// Bytes the blocks occupy (not counting spare vector capacity).
    pub fn memory_bytes(&self) -> usize {
        core::mem::size_of_val(self.blocks.as_slice())
    }

    /// The lanes of `blk` (within `valid`) that hold no triangle.
    #[inline(always)]
    fn others(&self, blk: &Tri4, valid: u32) -> u32 {
        if self.others {
            blk.nan_lanes() & valid
        } else {
            0
        }
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
        ray: &Ray4,
        t_max: f32,
        best: &mut Option<Hit>,
        other: impl FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
    ) -> f32 {
        self.closest_with(Portable, first, count, ray, t_max, best, other)
    }

    /// [`TriBlocks::closest`] with the SIMD tests of `simd`: a leaf's blocks are tested two at a
    /// time with [`Hit8::tri8`] (eight lanes in one AVX2 pass), an odd last block with the
    /// four-lane test. Lanes are visited in primitive order, so the result is the same. Lanes
    /// that hold no triangle go straight to `other`; blocks (or pairs) that hold no triangle at
    /// all skip the triangle test.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn closest_with<H: Hit8>(
        &self,
        simd: H,
        first: usize,
        count: usize,
        ray: &Ray4,
        mut t_max: f32,
        best: &mut Option<Hit>,
        mut other: impl FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
    ) -> f32 {
        let r4 = ray;
        let n = count.div_ceil(4);
        let mut k = 0;
        let mut found = |prim: usize, f: Option<(f32, Vec2)>, t_max: &mut f32| {
            if let Some((t, uv)) = f {
                *t_max = t;
                *best = Some(Hit {
                    t,
                    prim: prim as u32,
                    uv,
                });
            }
        };
        while k + 1 < n {
            let (a, b) = (&self.blocks[first + k], &self.blocks[first + k + 1]);
            let valid = Self::valid(k, count) | (Self::valid(k + 1, count) << 4);
            let others = self.others(a, valid) | self.others(b, valid >> 4) << 4;
            let blk = |lane: usize| if lane < 4 { a } else { b };
            if others == valid {
                let mut m = others;
                while m != 0 {
                    let lane = m.trailing_zeros() as usize;
                    m &= m - 1;
                    let prim = blk(lane).first as usize + (lane & 3);
                    found(prim, other(prim, &NOT_A_TRIANGLE, t_max), &mut t_max);
                }
            } else {
                let lanes = simd.tri8(a, b, r4, t_max);
                let mut m = (lanes.hit | lanes.fallback) & valid;
                while m != 0 {
                    let lane = m.trailing_zeros() as usize;
                    m &= m - 1;
                    let blk = blk(lane);
                    let prim = blk.first as usize + (lane & 3);
                    let f = if others & (1 << lane) != 0 {
                        other(prim, &NOT_A_TRIANGLE, t_max)
                    } else if lanes.fallback & (1 << lane) != 0 {
                        fallback(blk, lane & 3, r4, t_max)
                    } else if lanes.accepts(lane, t_max) {
                        Some((lanes.t[lane], Vec2::new(lanes.b[1][lane], lanes.b[2][lane])))
                    } else {
                        None
                    };
                    found(prim, f, &mut t_max);
                }
            }
            k += 2;
        }
        if k < n {
            let blk = &self.blocks[first + k];
            let valid = Self::valid(k, count);
            let others = self.others(blk, valid);
            if others == valid {
                let mut m = others;
                while m != 0 {
                    let lane = m.trailing_zeros() as usize;
                    m &= m - 1;
                    let prim = blk.first as usize + lane;
                    found(prim, other(prim, &NOT_A_TRIANGLE, t_max), &mut t_max);
                }
            } else {
                let lanes = simd.tri4(blk, r4, t_max);
                let mut m = (lanes.hit | lanes.fallback) & valid;
                while m != 0 {
                    let lane = m.trailing_zeros() as usize;
                    m &= m - 1;
                    let prim = blk.first as usize + lane;
                    let f = if others & (1 << lane) != 0 {
                        other(prim, &NOT_A_TRIANGLE, t_max)
                    } else if lanes.fallback & (1 << lane) != 0 {
                        fallback(blk, lane, r4, t_max)
                    } else if lanes.accepts(lane, t_max) {
                        Some((lanes.t[lane], Vec2::new(lanes.b[1][lane], lanes.b[2][lane])))
                    } else {
                        None
                    };
                    found(prim, f, &mut t_max);
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
        ray: &Ray4,
        t_max: f32,
        other: impl FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
    ) -> bool {
        self.any_with(Portable, first, count, ray, t_max, other)
    }

    /// [`TriBlocks::any`] with the SIMD tests of `simd` (blocks two at a time, as
    /// [`TriBlocks::closest_with`]; blocks without triangles skip the triangle test).
    #[inline(always)]
    pub(crate) fn any_with<H: Hit8>(
        &self,
        simd: H,
        first: usize,
        count: usize,
        ray: &Ray4,
        t_max: f32,
        mut other: impl FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
    ) -> bool {
        let r4 = ray;
        let n = count.div_ceil(4);
        let mut k = 0;
        while k < n {
            let a = &self.blocks[first + k];
            let pair = k + 1 < n;
            // The next block of the leaf, if any (else `a` again; its lanes are then not valid).
            let b = &self.blocks[first + k + usize::from(pair)];
            let (valid, others) = if pair {
                let valid = Self::valid(k, count) | (Self::valid(k + 1, count) << 4);
                (
                    valid,
                    self.others(a, valid) | self.others(b, valid >> 4) << 4,
                )
            } else {
                let valid = Self::valid(k, count);
                (valid, self.others(a, valid))
            };
            let fb = if others == valid {
                0
            } else {
                let (hit, fb) = if pair {
                    let lanes = simd.tri8(a, b, r4, t_max);
                    (lanes.hit, lanes.fallback)
                } else {
                    let lanes = simd.tri4(a, r4, t_max);
                    (lanes.hit, lanes.fallback)
                };
                if hit & valid != 0 {
                    return true;
                }
                fb & valid & !others
            };
            // Triangles left to the scalar test, then the other primitives.
            let mut m = fb;
            while m != 0 {
                let lane = m.trailing_zeros() as usize;
                m &= m - 1;
                let blk = if lane < 4 { a } else { b };
                if fallback(blk, lane & 3, r4, t_max).is_some() {
                    return true;
                }
            }
            let mut m = others;
            while m != 0 {
                let lane = m.trailing_zeros() as usize;
                m &= m - 1;
                let blk = if lane < 4 { a } else { b };
                let prim = blk.first as usize + (lane & 3);
                if other(prim, &NOT_A_TRIANGLE, t_max).is_some() {
                    return true;
                }
            }
            k += 2;
        }
        false
    }
}

/// A closest-hit cast's leaves for [`super::Bvh8::cast`]: the blocks, the ray's triangle-test
/// setup, the best hit so far, and the test of primitives that are not triangles.
pub struct ClosestLeaves<'a, F> {
    /// The blocks the leaves refer to.
    pub blocks: &'a TriBlocks,
    /// The ray's triangle-test setup, computed once per ray.
    pub ray: &'a Ray4,
    /// The closest hit so far.
    pub best: &'a mut Option<Hit>,
    /// The test of a primitive that is not a triangle (see [`TriBlocks::closest`]).
    pub other: F,
}

impl<F> Leaves for ClosestLeaves<'_, F>
where
    F: FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
{
    const RESTARTABLE: bool = true;

    #[inline(always)]
    fn prefetch(&self, first: usize, _count: usize) {
        prefetch_in(&self.blocks.blocks, first, core::mem::size_of::<Tri4>());
    }

    #[inline(always)]
    fn test<H: Hit8>(&mut self, simd: H, first: usize, count: usize, t_max: f32) -> Option<f32> {
        let other = &mut self.other;
        Some(
            self.blocks
                .closest_with(simd, first, count, self.ray, t_max, self.best, other),
        )
    }
}

/// An any-hit cast's leaves for [`super::Bvh8::cast`]; `hit` is set when one is found.
pub struct AnyLeaves<'a, F> {
    /// The blocks the leaves refer to.
    pub blocks: &'a TriBlocks,
    /// The ray's triangle-test setup, computed once per ray.
    pub ray: &'a Ray4,
    /// Whether a hit was found.
    pub hit: bool,
    /// The test of a primitive that is not a triangle (see [`TriBlocks::closest`]).
    pub other: F,
}

impl<F> Leaves for AnyLeaves<'_, F>
where
    F: FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>,
{
    const RESTARTABLE: bool = true;

    #[inline(always)]
    fn prefetch(&self, first: usize, _count: usize) {
        prefetch_in(&self.blocks.blocks, first, core::mem::size_of::<Tri4>());
    }

    #[inline(always)]
    fn test<H: Hit8>(&mut self, simd: H, first: usize, count: usize, t_max: f32) -> Option<f32> {
        let other = &mut self.other;
        self.hit = self
            .blocks
            .any_with(simd, first, count, self.ray, t_max, other);
        (!self.hit).then_some(t_max)
    }
}

/// The corners passed to `other` for a primitive that is not a triangle.
const NOT_A_TRIANGLE: [Vec3; 3] = [Vec3::NAN; 3];

/// The scalar test of a triangle lane the four-lane test left undecided (an edge function
/// exactly zero: rare, so kept out of the loop).
#[inline(never)]
fn fallback(blk: &Tri4, lane: usize, ray: &Ray4, t_max: f32) -> Option<(f32, Vec2)> {
    let [p0, p1, p2] = blk.corners(lane);
    ray.tri()
        .intersect(t_max, p0, p1, p2)
        .map(|(t, _, b1, b2)| (t, Vec2::new(b1, b2)))
}

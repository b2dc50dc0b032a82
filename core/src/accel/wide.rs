//! An 8-wide BVH: the binary SAH hierarchy collapsed so each node holds up to eight children,
//! whose boxes are stored in SoA layout and tested against a ray at once ([`super::slab_simd`]:
//! AVX2 where the CPU has it, detected once per build, else a portable test with the same bits).
//!
//! Closest-hit traversal visits the children a ray meets nearest entry first, postponing the
//! others on a stack with their entry distance and skipping them when popped if a closer hit has
//! been found; any hit stops at the first hit. Nodes are stored depth
//! first, the root at index 0; a child is either an interior node (its index) or a leaf (a range
//! of the primitive order returned by the build).
use super::entry::{nearest_first, Entry};
use super::leaves::FnLeaves;
use super::slab::RayPre;
use super::slab_simd::{prefetch_in, Avx2, Hit8, Portable, WithHit8};
use super::wide_node::Bvh8Node;
use super::{BuildParams, Bvh, Collapse, Fork, InTurn, Leaves};
use crate::math::{Aabb, Ray};
use alloc::vec::Vec;

/// The 8-wide hierarchy.
#[derive(Clone, Debug)]
pub struct Bvh8 {
    /// Nodes, root first (empty for an empty scene).
    pub nodes: Vec<Bvh8Node>,
    bounds: Aabb,
    /// Nodes on the longest root-to-leaf path.
    depth: usize,
    /// Whether to run the AVX2 box test (detected when built).
    avx2: Option<Avx2>,
}

impl Default for Bvh8 {
    fn default() -> Self {
        Bvh8 {
            nodes: Vec::new(),
            bounds: Aabb::EMPTY,
            depth: 0,
            avx2: None,
        }
    }
}

/// Entries of the traversal stack kept in the function's frame. A node pushes at most 7 entries
/// and a path has `depth` nodes, so `7 * depth + 1` entries always suffice: hierarchies up to
/// depth 4 use a quarter of this array, up to depth 9 (millions of triangles) half, up to depth
/// 18 all of it, deeper ones a heap stack. Kept small because it is initialised per ray.
const STACK: usize = 128;

/// The stack a restartable traversal ([`Leaves::RESTARTABLE`]) tries first.
const SMALL_STACK: usize = 16;

impl Bvh8 {
    /// The binary build's leaf-size trade-off, for leaves of four-triangle blocks
    /// ([`super::tri_block`]): a leaf of `n` primitives costs `ceil(n / 4)` block tests, one
    /// traversal step a quarter of one. Measured on the 4-wide BVH that preceded this one
    /// (`BVH_PARAMS` in `--bench bvh_compare`, callgrind and renders of the Cornell box): with
    /// block costs the SAH fills blocks (49-57 bytes per triangle instead of 71-75); costs 0.5
    /// and 1 rendered the Cornell box 5-10% slower than leaves of at most 4 scalar tests, cost
    /// 0.25 3-5% faster, and it casts bench rays as fast as 0.5.
    pub const PARAMS: BuildParams = BuildParams {
        max_leaf: 16,
        traversal_cost: 0.25,
        block: 4,
    };

    /// Builds the binary SAH hierarchy (with [`Bvh8::PARAMS`]) and collapses it; returns the
    /// hierarchy and the order in which the caller must store its primitives (leaves refer to
    /// ranges of that order).
    pub fn build(bounds: &[Aabb]) -> (Bvh8, Vec<u32>) {
        Bvh8::build_with(bounds, Bvh8::PARAMS)
    }

    /// [`Bvh8::build`] with a chosen leaf-size trade-off.
    pub fn build_with(bounds: &[Aabb], params: BuildParams) -> (Bvh8, Vec<u32>) {
        Bvh8::build_collapsed(bounds, params, Collapse::DEFAULT)
    }

    /// [`Bvh8::build`] with a chosen leaf-size trade-off and collapse.
    pub fn build_collapsed(
        bounds: &[Aabb],
        params: BuildParams,
        how: Collapse,
    ) -> (Bvh8, Vec<u32>) {
        Bvh8::build_forked(bounds, params, how, &InTurn)
    }

    /// [`Bvh8::build_collapsed`], the binary build's large halves run through `fork` (see
    /// [`Bvh::build_forked`]): the same hierarchy whatever the fork does.
    pub fn build_forked(
        bounds: &[Aabb],
        params: BuildParams,
        how: Collapse,
        fork: &dyn Fork,
    ) -> (Bvh8, Vec<u32>) {
        let (bin, order) = Bvh::build_forked(bounds, params, fork);
        (Bvh8::from_binary_with(&bin, how), order)
    }

    /// Collapses a binary hierarchy into 8-wide nodes as `how` says (leaves are ranges of the
    /// binary build's primitive order). Detects AVX2 for the traversal.
    pub fn from_binary_with(bin: &Bvh, how: Collapse) -> Bvh8 {
        let (nodes, depth) = if bin.nodes.is_empty() {
            (Vec::new(), 0)
        } else {
            how.run(bin)
        };
        Bvh8 {
            nodes,
            bounds: bin.bounds(),
            depth,
            avx2: Avx2::detect(),
        }
    }

    /// Whether traversal uses the AVX2 box test (else the portable one, which gives the same
    /// results).
    pub fn uses_avx2(&self) -> bool {
        self.avx2.is_some()
    }

    /// The AVX2 token traversal uses, if any (other SIMD code of a render follows its choice,
    /// so that [`Bvh8::use_portable`] makes the whole render portable).
    pub fn avx2(&self) -> Option<Avx2> {
        self.avx2
    }

    /// Makes traversal use the portable box test (for tests and measurements).
    pub fn use_portable(&mut self) {
        self.avx2 = None;
    }

    /// Replaces each leaf's first primitive by `f(first, count)` (e.g. the index of its first
    /// block of primitives), visiting leaves in node order.
    pub fn map_leaves(&mut self, mut f: impl FnMut(usize, usize) -> u32) {
        for node in &mut self.nodes {
            for lane in 0..8 {
                if node.used & (1 << lane) != 0 && node.count[lane] > 0 {
                    node.child[lane] = f(node.child[lane] as usize, usize::from(node.count[lane]));
                }
            }
        }
    }

    /// Bytes the hierarchy's nodes occupy (not counting the primitives it indexes, nor spare
    /// vector capacity).
    pub fn memory_bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes.as_slice())
    }

    /// Nodes on the longest path from the root to a leaf.
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// Bounds of the whole hierarchy.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Closest-hit traversal: visits the leaves the ray may reach, nearest entry first;
    /// `leaf(first, count, t_max)` tests the primitives and returns the new `t_max`.
    #[inline]
    pub fn traverse_closest(&self, ray: &Ray, mut leaf: impl FnMut(usize, usize, f32) -> f32) {
        self.walk::<false, false>(ray, FnLeaves(|f, c, t| Some(leaf(f, c, t))), &mut 0);
    }

    /// Any-hit traversal: `leaf(first, count, t_max)` returns true to stop (a hit was found).
    #[inline]
    pub fn traverse_any(&self, ray: &Ray, mut leaf: impl FnMut(usize, usize, f32) -> bool) {
        let leaf = |f, c, t| if leaf(f, c, t) { None } else { Some(t) };
        self.walk::<true, false>(ray, FnLeaves(leaf), &mut 0);
    }

    /// [`Bvh8::traverse_closest`] that also adds the number of nodes it visits to `nodes` (for
    /// statistics; the uncounted walk compiles without the counter).
    #[inline]
    pub fn traverse_closest_counted(
        &self,
        ray: &Ray,
        mut leaf: impl FnMut(usize, usize, f32) -> f32,
        nodes: &mut u64,
    ) {
        self.walk::<false, true>(ray, FnLeaves(|f, c, t| Some(leaf(f, c, t))), nodes);
    }

    /// [`Bvh8::traverse_any`] that also adds the number of nodes it visits to `nodes`.
    #[inline]
    pub fn traverse_any_counted(
        &self,
        ray: &Ray,
        mut leaf: impl FnMut(usize, usize, f32) -> bool,
        nodes: &mut u64,
    ) {
        let leaf = |f, c, t| if leaf(f, c, t) { None } else { Some(t) };
        self.walk::<true, true>(ray, FnLeaves(leaf), nodes);
    }

    /// A traversal whose leaves are tested by `leaves` with the SIMD tests the traversal is
    /// compiled for (AVX2 where detected), inlined into its loop: closest hit (`ANY == false`:
    /// visits nearest entry first, `leaves` returns the new `t_max`) or any hit (`ANY`: stops
    /// when `leaves` returns `None`).
    #[inline]
    pub fn cast<const ANY: bool>(&self, ray: &Ray, leaves: impl Leaves) {
        self.walk::<ANY, false>(ray, leaves, &mut 0);
    }

    /// Picks the box test (one traversal loop is compiled per test) and the stack size.
    /// Always inlined, so the caller builds the [`Walk`] the AVX2 function receives in place;
    /// out of line, the leaves were copied into it with one 32-byte load of fields just stored
    /// one by one, which the processor cannot forward (a stall per ray).
    #[inline(always)]
    fn walk<const ANY: bool, const COUNT: bool>(
        &self,
        ray: &Ray,
        leaf: impl Leaves,
        nodes: &mut u64,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let walk = Walk::<_, ANY, COUNT> {
            bvh: self,
            ray,
            leaf,
            nodes,
        };
        match self.avx2 {
            Some(avx2) => avx2.run(walk),
            None => walk.call(Portable),
        }
    }

    #[inline(always)]
    fn walk_sized<const ANY: bool, const COUNT: bool, H: Hit8, L: Leaves>(
        &self,
        test: H,
        ray: &Ray,
        mut leaf: L,
        nodes: &mut u64,
    ) {
        if self.nodes.len() == 1 {
            // Small scenes: no stack (accel/root.rs).
            self.walk_root::<ANY, COUNT, H, L>(test, ray, leaf, nodes);
            return;
        }
        let need = 7 * self.depth + 1;
        if L::RESTARTABLE && !COUNT && need > SMALL_STACK {
            // Most rays: a small stack; the rare ray that overflows it starts again below.
            let stack = &mut [Entry::default(); SMALL_STACK];
            if self.walk_with::<ANY, COUNT, H>(test, ray, stack, &mut leaf, nodes) {
                return;
            }
        }
        if need <= STACK / 4 {
            // Small scenes (the Cornell box): zeroing 32 entries is a few stores, not a memset.
            let stack = &mut [Entry::default(); STACK / 4];
            self.walk_with::<ANY, COUNT, H>(test, ray, stack, leaf, nodes);
        } else if need <= STACK / 2 {
            let stack = &mut [Entry::default(); STACK / 2];
            self.walk_with::<ANY, COUNT, H>(test, ray, stack, leaf, nodes);
        } else if need <= STACK {
            let stack = &mut [Entry::default(); STACK];
            self.walk_with::<ANY, COUNT, H>(test, ray, stack, leaf, nodes);
        } else {
            let stack = &mut alloc::vec![Entry::default(); need];
            self.walk_with::<ANY, COUNT, H>(test, ray, stack, leaf, nodes);
        }
    }

    #[inline(always)]
    fn walk_with<const ANY: bool, const COUNT: bool, H: Hit8>(
        &self,
        test: H,
        ray: &Ray,
        stack: &mut [Entry],
        mut leaf: impl Leaves,
        nodes: &mut u64,
    ) -> bool {
        let pre = RayPre::new(ray);
        let mut t_max = ray.t_max;
        let mut sp = 0usize;
        let mut cur = Entry::default(); // the root node
        loop {
            if cur.count == 0 {
                if COUNT {
                    *nodes += 1;
                }
                let node = &self.nodes[cur.child as usize];
                let (mask, t_near) = test.hit8(&node.boxes, &pre, t_max);
                let mut mask = mask & node.used;
                // Start loading every child hit, before the work of ordering them: the nearest is
                // next, most others follow (measured: prefetching only the postponed ones, which
                // costs fewer instructions, was slower).
                let mut hit_leaves = mask & node.leaves;
                while hit_leaves != 0 {
                    let lane = hit_leaves.trailing_zeros() as usize;
                    hit_leaves &= hit_leaves - 1;
                    leaf.prefetch(node.child[lane] as usize, usize::from(node.count[lane]));
                }
                let mut hit_nodes = mask & !node.leaves;
                while hit_nodes != 0 {
                    let lane = hit_nodes.trailing_zeros() as usize;
                    hit_nodes &= hit_nodes - 1;
                    // The boxes (the first three lines), which the node test reads first.
                    prefetch_in(&self.nodes, node.child[lane] as usize, 192);
                }
                if mask != 0 {
                    let entry = |lane: usize| Entry {
                        child: node.child[lane],
                        count: u32::from(node.count[lane]),
                        t_near: t_near[lane],
                    };
                    if sp + mask.count_ones() as usize > stack.len() {
                        // Only a restartable walk's small stack can overflow (see `STACK`).
                        return false;
                    }
                    if ANY {
                        cur = entry(mask.trailing_zeros() as usize);
                        mask &= mask - 1;
                        while mask != 0 {
                            stack[sp] = entry(mask.trailing_zeros() as usize);
                            sp += 1;
                            mask &= mask - 1;
                        }
                        continue;
                    }
                    if mask & (mask - 1) == 0 {
                        // One child hit (the common case deep down): no sorting.
                        cur = entry(mask.trailing_zeros() as usize);
                        continue;
                    }
                    cur = nearest_first(mask, entry, stack, &mut sp);
                    continue;
                }
            } else {
                match leaf.test(test, cur.child as usize, cur.count as usize, t_max) {
                    Some(t) => t_max = t,
                    None => return true,
                }
            }
            loop {
                if sp == 0 {
                    return true;
                }
                sp -= 1;
                cur = stack[sp];
                // A child entered beyond the closest hit so far cannot hold a closer one.
                if ANY || cur.t_near <= t_max {
                    break;
                }
            }
        }
    }
}

/// One traversal's arguments, to be run with either box test.
struct Walk<'a, L, const ANY: bool, const COUNT: bool> {
    bvh: &'a Bvh8,
    ray: &'a Ray,
    leaf: L,
    nodes: &'a mut u64,
}

impl<L: Leaves, const ANY: bool, const COUNT: bool> WithHit8 for Walk<'_, L, ANY, COUNT> {
    type Output = ();

    #[inline(always)]
    fn call<H: Hit8>(self, test: H) {
        self.bvh
            .walk_sized::<ANY, COUNT, H, L>(test, self.ray, self.leaf, self.nodes);
    }
}

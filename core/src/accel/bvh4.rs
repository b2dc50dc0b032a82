//! A 4-wide BVH: the binary SAH hierarchy collapsed so each node holds up to four children,
//! whose boxes are stored in SoA layout and tested against a ray at once ([`super::simd`]).
//!
//! Closest-hit traversal is ordered: the children a ray meets are visited nearest entry first,
//! and the others wait on a stack with their entry distance, skipped when popped if a hit closer
//! than that entry has been found meanwhile. Any-hit traversal skips the sorting and stops at the
//! first hit. Nodes are stored depth first, the root at index 0; a child is either an interior
//! node (its index) or a leaf (a range of the primitive order returned by the build).
use super::simd::{hit4, Boxes4, RayPre, MAX_X, MIN_X};
use super::{BuildParams, Bvh};
use crate::math::{Aabb, Ray};
use alloc::vec::Vec;
use glam::Vec3;

/// A node: four child boxes, and per child its node index (`count == 0`) or its leaf's first
/// primitive and primitive count. 128 bytes, two cache lines.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct Bvh4Node {
    /// The children's boxes; unused lanes hold the empty box.
    pub boxes: Boxes4,
    /// Interior child: its node index. Leaf: its first primitive. Unused: `u32::MAX`.
    pub child: [u32; 4],
    /// Leaf: number of primitives (at least 1). Interior or unused: 0.
    pub count: [u16; 4],
    /// Bit `i` set when lane `i` is used (used lanes come first).
    pub used: u32,
}

// Two cache lines, as the memory figures assume.
const _: () = assert!(core::mem::size_of::<Bvh4Node>() == 128);

impl Bvh4Node {
    const EMPTY: Bvh4Node = Bvh4Node {
        boxes: Boxes4::EMPTY,
        child: [u32::MAX; 4],
        count: [0; 4],
        used: 0,
    };

    fn set_box(&mut self, lane: usize, b: Aabb) {
        for a in 0..3 {
            self.boxes.b[MIN_X + a][lane] = b.min[a];
            self.boxes.b[MAX_X + a][lane] = b.max[a];
        }
    }

    /// Box of child `lane`.
    pub fn child_bounds(&self, lane: usize) -> Aabb {
        let b = &self.boxes.b;
        Aabb {
            min: Vec3::new(b[MIN_X][lane], b[MIN_X + 1][lane], b[MIN_X + 2][lane]),
            max: Vec3::new(b[MAX_X][lane], b[MAX_X + 1][lane], b[MAX_X + 2][lane]),
        }
    }
}

/// The 4-wide hierarchy.
#[derive(Clone, Debug)]
pub struct Bvh4 {
    /// Nodes, root first (empty for an empty scene).
    pub nodes: Vec<Bvh4Node>,
    bounds: Aabb,
    /// Nodes on the longest root-to-leaf path.
    depth: usize,
}

impl Default for Bvh4 {
    fn default() -> Self {
        Bvh4 {
            nodes: Vec::new(),
            bounds: Aabb::EMPTY,
            depth: 0,
        }
    }
}

/// A postponed child: node index or first primitive, leaf count (0 for a node), entry distance.
#[derive(Clone, Copy, Default)]
struct Entry {
    child: u32,
    count: u32,
    t_near: f32,
}

/// Entries of the traversal stack kept in the function's frame. A node pushes at most 3 entries
/// and a path has `depth` nodes, so `3 * depth + 1` entries always suffice: hierarchies up to
/// depth 10 (a million triangles) use half this array, up to depth 21 all of it, deeper ones (the
/// binary build reaches depth 60 only for pathological inputs) a heap stack. Kept small because
/// it is initialised per ray.
const STACK: usize = 64;

impl Bvh4 {
    /// Builds the binary SAH hierarchy and collapses it; returns the hierarchy and the order in
    /// which the caller must store its primitives (leaves refer to ranges of that order).
    pub fn build(bounds: &[Aabb]) -> (Bvh4, Vec<u32>) {
        Bvh4::build_with(bounds, super::Bvh8::PARAMS)
    }

    /// [`Bvh4::build`] with a chosen leaf-size trade-off.
    pub fn build_with(bounds: &[Aabb], params: BuildParams) -> (Bvh4, Vec<u32>) {
        let (bin, order) = Bvh::build_with(bounds, params);
        (Bvh4::from_binary(&bin), order)
    }

    /// Collapses a binary hierarchy: each node takes its binary children and keeps replacing the
    /// interior child of largest surface area by that child's two children while it has fewer
    /// than four. Leaves (primitive ranges) are unchanged.
    pub fn from_binary(bin: &Bvh) -> Bvh4 {
        let mut nodes = Vec::with_capacity(bin.nodes.len() / 3 + 1);
        let mut depth = 0;
        if !bin.nodes.is_empty() {
            collapse(bin, 0, 1, &mut depth, &mut nodes);
        }
        Bvh4 {
            nodes,
            bounds: bin.bounds(),
            depth,
        }
    }

    /// Replaces each leaf's first primitive by `f(first, count)` (e.g. the index of its first
    /// block of primitives), visiting leaves in node order.
    pub fn map_leaves(&mut self, mut f: impl FnMut(usize, usize) -> u32) {
        for node in &mut self.nodes {
            for lane in 0..4 {
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
        self.walk::<false, false>(ray, |f, c, t| Some(leaf(f, c, t)), &mut 0);
    }

    /// Any-hit traversal: `leaf(first, count, t_max)` returns true to stop (a hit was found).
    #[inline]
    pub fn traverse_any(&self, ray: &Ray, mut leaf: impl FnMut(usize, usize, f32) -> bool) {
        let leaf = |f, c, t| if leaf(f, c, t) { None } else { Some(t) };
        self.walk::<true, false>(ray, leaf, &mut 0);
    }

    /// [`Bvh4::traverse_closest`] that also adds the number of nodes it visits to `nodes` (for
    /// statistics; the uncounted walk compiles without the counter).
    #[inline]
    pub fn traverse_closest_counted(
        &self,
        ray: &Ray,
        mut leaf: impl FnMut(usize, usize, f32) -> f32,
        nodes: &mut u64,
    ) {
        self.walk::<false, true>(ray, |f, c, t| Some(leaf(f, c, t)), nodes);
    }

    /// [`Bvh4::traverse_any`] that also adds the number of nodes it visits to `nodes`.
    #[inline]
    pub fn traverse_any_counted(
        &self,
        ray: &Ray,
        mut leaf: impl FnMut(usize, usize, f32) -> bool,
        nodes: &mut u64,
    ) {
        let leaf = |f, c, t| if leaf(f, c, t) { None } else { Some(t) };
        self.walk::<true, true>(ray, leaf, nodes);
    }

    #[inline]
    fn walk<const ANY: bool, const COUNT: bool>(
        &self,
        ray: &Ray,
        leaf: impl FnMut(usize, usize, f32) -> Option<f32>,
        nodes: &mut u64,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let need = 3 * self.depth + 1;
        if need <= STACK / 4 {
            // Small scenes (the Cornell box): zeroing 16 entries is a few stores, not a memset.
            self.walk_with::<ANY, COUNT>(ray, &mut [Entry::default(); STACK / 4], leaf, nodes);
        } else if need <= STACK / 2 {
            self.walk_with::<ANY, COUNT>(ray, &mut [Entry::default(); STACK / 2], leaf, nodes);
        } else if need <= STACK {
            self.walk_with::<ANY, COUNT>(ray, &mut [Entry::default(); STACK], leaf, nodes);
        } else {
            self.walk_with::<ANY, COUNT>(
                ray,
                &mut alloc::vec![Entry::default(); need],
                leaf,
                nodes,
            );
        }
    }

    #[inline(always)]
    fn walk_with<const ANY: bool, const COUNT: bool>(
        &self,
        ray: &Ray,
        stack: &mut [Entry],
        mut leaf: impl FnMut(usize, usize, f32) -> Option<f32>,
        nodes: &mut u64,
    ) {
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
                let (mask, t_near) = hit4(&node.boxes, &pre, t_max);
                let mut mask = mask & node.used;
                if mask != 0 {
                    let entry = |lane: usize| Entry {
                        child: node.child[lane],
                        count: u32::from(node.count[lane]),
                        t_near: t_near[lane],
                    };
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
                    // Sort the (at most four) hit children by entry distance, nearest first.
                    let mut hits = [Entry::default(); 4];
                    let mut n = 0;
                    while mask != 0 {
                        let e = entry(mask.trailing_zeros() as usize);
                        mask &= mask - 1;
                        let mut j = n;
                        while j > 0 && hits[j - 1].t_near > e.t_near {
                            hits[j] = hits[j - 1];
                            j -= 1;
                        }
                        hits[j] = e;
                        n += 1;
                    }
                    for e in hits[1..n].iter().rev() {
                        stack[sp] = *e;
                        sp += 1;
                    }
                    cur = hits[0];
                    continue;
                }
            } else {
                match leaf(cur.child as usize, cur.count as usize, t_max) {
                    Some(t) => t_max = t,
                    None => return,
                }
            }
            loop {
                if sp == 0 {
                    return;
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

fn collapse(
    bin: &Bvh,
    at: usize,
    depth: usize,
    max_depth: &mut usize,
    nodes: &mut Vec<Bvh4Node>,
) -> u32 {
    *max_depth = (*max_depth).max(depth);
    let (kids, k) = super::collapse::greedy_children::<4>(bin, at);
    let me = nodes.len();
    nodes.push(Bvh4Node::EMPTY);
    for (lane, &c) in kids[..k].iter().enumerate() {
        let cn = &bin.nodes[c];
        let (child, count) = if cn.count > 0 {
            (cn.offset, cn.count)
        } else {
            (collapse(bin, c, depth + 1, max_depth, nodes), 0)
        };
        let node = &mut nodes[me];
        node.set_box(lane, cn.bounds);
        node.child[lane] = child;
        node.count[lane] = count;
        node.used |= 1 << lane;
    }
    me as u32
}

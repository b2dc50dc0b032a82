//! The binary bounding volume hierarchy, built with the binned surface-area heuristic: the tree
//! the 8-wide one (`wide`) is collapsed from, and a traversal of its own for comparisons.
//!
//! Nodes are stored depth first: an interior node's first child follows it, the second child's
//! index is stored. Traversal visits the near child first (by the ray direction's sign on the
//! split axis) and keeps a fixed-size stack: no allocation per ray.
use super::fork::{Fork, InTurn};
use crate::math::{Aabb, Ray};
use alloc::vec::Vec;
use glam::Vec3;

const BINS: usize = 16;
const MAX_DEPTH: usize = 60;

/// Ranges of at least this many primitives have their two halves built through the [`Fork`]
/// (a thread costs tens of microseconds; a range this size, about a millisecond).
const FORK_MIN: usize = 4096;

/// How the SAH build trades node visits against primitive tests.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildParams {
    /// Ranges of at most this many primitives may become leaves when the SAH says so.
    pub max_leaf: usize,
    /// Cost of one traversal step relative to one leaf test (of `block` primitives).
    pub traversal_cost: f32,
    /// Primitives tested at once: a leaf of `n` primitives costs `ceil(n / block)` tests, so the
    /// heuristic prefers leaves that fill whole blocks (1 for one-at-a-time tests).
    pub block: usize,
}

impl BuildParams {
    /// For binary traversal (one box per step): small leaves.
    pub(crate) const BINARY: BuildParams = BuildParams {
        max_leaf: 4,
        traversal_cost: 0.5,
        block: 1,
    };

    /// Leaf cost in units of one block test: `ceil(n / block)`.
    #[inline]
    fn leaf_cost(&self, n: usize) -> f32 {
        n.div_ceil(self.block.max(1)) as f32
    }
}

/// A node: its box, and either a primitive range (leaf, `count > 0`) or the second child.
#[derive(Clone, Copy, Debug)]
pub struct BvhNode {
    /// Bounds of everything below.
    pub bounds: Aabb,
    /// Leaf: first primitive. Interior: index of the second child.
    pub offset: u32,
    /// Leaf: number of primitives. Interior: 0.
    pub count: u16,
    /// Interior: split axis.
    pub axis: u16,
}

/// The hierarchy; primitives are referred to by their position in the build order.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// Nodes, root first (empty for an empty scene).
    pub nodes: Vec<BvhNode>,
}

struct Item {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
}

impl Bvh {
    /// Builds over primitive boxes; returns the hierarchy and the order in which the caller must
    /// store its primitives (leaves refer to ranges of that order).
    pub fn build(bounds: &[Aabb]) -> (Bvh, Vec<u32>) {
        Bvh::build_with(bounds, BuildParams::BINARY)
    }

    /// [`Bvh::build`] with chosen leaf-size trade-off.
    pub fn build_with(bounds: &[Aabb], params: BuildParams) -> (Bvh, Vec<u32>) {
        Bvh::build_forked(bounds, params, &InTurn)
    }

    /// [`Bvh::build_with`], the halves of large ranges built through `fork` (perhaps at once):
    /// the same hierarchy whatever the fork does.
    pub fn build_forked(bounds: &[Aabb], params: BuildParams, fork: &dyn Fork) -> (Bvh, Vec<u32>) {
        let mut items: Vec<Item> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| Item {
                bounds: *b,
                centroid: b.centroid(),
                index: i as u32,
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * items.len().max(1));
        if !items.is_empty() {
            let range = RangeBounds::of(&items);
            let build = Build {
                params: &params,
                fork,
            };
            build_node(&build, &mut items, 0, range, 0, &mut nodes);
        }
        (Bvh { nodes }, items.iter().map(|it| it.index).collect())
    }

    /// Bytes the hierarchy's nodes occupy (not counting the primitive array it indexes, nor
    /// spare vector capacity).
    pub fn memory_bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes.as_slice())
    }

    /// Bounds of the whole hierarchy.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// Visits leaves the ray may reach, near first; `leaf(first, count, t_max)` tests the
    /// primitives and returns the new `t_max` (or `None` to stop, for any-hit queries).
    #[inline]
    pub fn traverse(&self, ray: &Ray, mut leaf: impl FnMut(usize, usize, f32) -> Option<f32>) {
        if self.nodes.is_empty() {
            return;
        }
        let inv_d = Vec3::ONE / ray.d;
        let neg = [inv_d.x < 0.0, inv_d.y < 0.0, inv_d.z < 0.0];
        let mut t_max = ray.t_max;
        let mut stack = [0u32; 64];
        let mut sp = 0usize;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.bounds.hit(ray, inv_d, t_max).is_some() {
                if n.count > 0 {
                    match leaf(n.offset as usize, n.count as usize, t_max) {
                        Some(t) => t_max = t,
                        None => return,
                    }
                } else {
                    let (near, far) = if neg[n.axis as usize] {
                        (n.offset as usize, node + 1)
                    } else {
                        (node + 1, n.offset as usize)
                    };
                    stack[sp] = far as u32;
                    sp += 1;
                    node = near;
                    continue;
                }
            }
            if sp == 0 {
                return;
            }
            sp -= 1;
            node = stack[sp] as usize;
        }
    }
}

fn make_leaf(start: usize, end: usize, bounds: Aabb, nodes: &mut Vec<BvhNode>) {
    nodes.push(BvhNode {
        bounds,
        offset: start as u32,
        count: (end - start) as u16,
        axis: 0,
    });
}

/// The boxes around a range of items and around their centroids.
#[derive(Clone, Copy)]
struct RangeBounds {
    bounds: Aabb,
    centroids: Aabb,
}

impl RangeBounds {
    fn of(items: &[Item]) -> RangeBounds {
        RangeBounds {
            bounds: items.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds)),
            centroids: items.iter().fold(Aabb::EMPTY, |b, it| b.grow(it.centroid)),
        }
    }
}

/// The items whose centroids fall in one bin along one axis.
#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: usize,
}

impl Bin {
    const EMPTY: Bin = Bin {
        bounds: Aabb::EMPTY,
        count: 0,
    };

    /// Adds `count` items whose union is `bounds`.
    #[inline(always)]
    fn add(&mut self, bounds: Aabb, count: usize) {
        self.bounds = self.bounds.union(bounds);
        self.count += count;
    }
}

/// The cheapest split found: its SAH cost, axis, last bin of the left side, and the boxes of
/// the two sides (the unions of their bins, which are the unions of their items).
struct Split {
    cost: f32,
    axis: usize,
    bin: usize,
    left: Aabb,
    right: Aabb,
}

/// The bin of a centroid coordinate `c` along an axis whose centroids start at `min` (`scale`
/// is `BINS` over the centroids' extent).
#[inline(always)]
fn bin_of(c: f32, min: f32, scale: f32) -> usize {
    (((c - min) * scale) as usize).min(BINS - 1)
}

/// Bins the items along every axis of positive centroid extent in one pass over them, then
/// sweeps each axis's bins for the cheapest split.
fn best_split(slice: &[Item], cb: &Aabb, params: &BuildParams) -> Option<Split> {
    let ext = cb.extent();
    let axes: [bool; 3] =
        core::array::from_fn(|a| ext[a].partial_cmp(&0.0) == Some(core::cmp::Ordering::Greater));
    let scale: [f32; 3] = core::array::from_fn(|a| BINS as f32 / ext[a]);
    let mut bins = [[Bin::EMPTY; BINS]; 3];
    for it in slice {
        for axis in 0..3 {
            if axes[axis] {
                bins[axis][bin_of(it.centroid[axis], cb.min[axis], scale[axis])].add(it.bounds, 1);
            }
        }
    }
    let mut best: Option<Split> = None;
    for axis in (0..3).filter(|&a| axes[a]) {
        let bins = &bins[axis];
        // Sweep from the right to get the suffix boxes, then from the left.
        let mut right = [Bin::EMPTY; BINS];
        let mut acc = Bin::EMPTY;
        for i in (1..BINS).rev() {
            acc.add(bins[i].bounds, bins[i].count);
            right[i] = acc;
        }
        let mut left = Bin::EMPTY;
        for i in 0..BINS - 1 {
            left.add(bins[i].bounds, bins[i].count);
            let r = &right[i + 1];
            if left.count == 0 || r.count == 0 {
                continue;
            }
            let cost = left.bounds.area() * params.leaf_cost(left.count)
                + r.bounds.area() * params.leaf_cost(r.count);
            if best.as_ref().is_none_or(|b| cost < b.cost) {
                best = Some(Split {
                    cost,
                    axis,
                    bin: i,
                    left: left.bounds,
                    right: r.bounds,
                });
            }
        }
    }
    best
}

/// What every step of a build shares.
struct Build<'a> {
    params: &'a BuildParams,
    fork: &'a dyn Fork,
}

/// Builds the subtree over `items` (the build order's positions `base..base + items.len()`)
/// into `nodes`, depth first; interior nodes refer to their second child by its index in
/// `nodes`.
fn build_node(
    b: &Build,
    items: &mut [Item],
    base: usize,
    range: RangeBounds,
    depth: usize,
    nodes: &mut Vec<BvhNode>,
) {
    let params = b.params;
    let RangeBounds {
        bounds,
        centroids: cb,
    } = range;
    let count = items.len();
    let end = base + count;
    if count == 1 || depth >= MAX_DEPTH && count <= u16::MAX as usize {
        return make_leaf(base, end, bounds, nodes);
    }
    let area = bounds.area();
    let split = match best_split(items, &cb, params) {
        Some(sp) => {
            let split_cost = params.traversal_cost + if area > 0.0 { sp.cost / area } else { 0.0 };
            if count <= params.max_leaf && split_cost >= params.leaf_cost(count) {
                return make_leaf(base, end, bounds, nodes);
            }
            let (axis, bin) = (sp.axis, sp.bin);
            let scale = BINS as f32 / cb.extent()[axis];
            let minc = cb.min[axis];
            let (mid, lc, rc) =
                partition(items, |it| bin_of(it.centroid[axis], minc, scale) <= bin);
            let left = RangeBounds {
                bounds: sp.left,
                centroids: lc,
            };
            let right = RangeBounds {
                bounds: sp.right,
                centroids: rc,
            };
            Some((axis, mid, left, right))
        }
        None => None,
    };
    let (axis, mid, left, right) = match split {
        Some(s) if s.1 > 0 && s.1 < count => s,
        _ => {
            // All centroids coincide: a leaf if small, else split by index to bound leaf size.
            if count <= params.max_leaf * 4 {
                return make_leaf(base, end, bounds, nodes);
            }
            let mid = count / 2;
            let (left, right) = (
                RangeBounds::of(&items[..mid]),
                RangeBounds::of(&items[mid..]),
            );
            (0, mid, left, right)
        }
    };
    let me = nodes.len();
    nodes.push(BvhNode {
        bounds,
        offset: 0,
        count: 0,
        axis: axis as u16,
    });
    let (l, r) = items.split_at_mut(mid);
    if count < FORK_MIN {
        build_node(b, l, base, left, depth + 1, nodes);
        nodes[me].offset = nodes.len() as u32;
        build_node(b, r, base + mid, right, depth + 1, nodes);
        return;
    }
    // Each half into a list of its own (its indices counted from 0), joined in order after.
    let (mut ln, mut rn) = (Vec::new(), Vec::new());
    b.fork.join(
        &mut || build_node(b, l, base, left, depth + 1, &mut ln),
        &mut || build_node(b, r, base + mid, right, depth + 1, &mut rn),
    );
    append_shifted(nodes, ln);
    nodes[me].offset = nodes.len() as u32;
    append_shifted(nodes, rn);
}

/// Appends `sub`, a subtree built with indices counted from 0, to `nodes`, its interior nodes'
/// second-child indices moved to where it lands.
fn append_shifted(nodes: &mut Vec<BvhNode>, sub: Vec<BvhNode>) {
    let shift = nodes.len() as u32;
    nodes.extend(sub.into_iter().map(|mut n| {
        if n.count == 0 {
            n.offset += shift;
        }
        n
    }));
}

/// Moves the items for which `pred` holds to the front (in the order a swapping scan leaves
/// them); returns how many there are and the boxes around the centroids of each side.
fn partition(items: &mut [Item], pred: impl Fn(&Item) -> bool) -> (usize, Aabb, Aabb) {
    let mut first = 0;
    let (mut lc, mut rc) = (Aabb::EMPTY, Aabb::EMPTY);
    for i in 0..items.len() {
        if pred(&items[i]) {
            lc = lc.grow(items[i].centroid);
            items.swap(first, i);
            first += 1;
        } else {
            rc = rc.grow(items[i].centroid);
        }
    }
    (first, lc, rc)
}

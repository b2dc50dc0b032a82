//! Collapsing the binary SAH hierarchy into 8-wide nodes (`Bvh8`), two ways:
//!
//! - [`Collapse::Greedy`]: each node takes its binary children and keeps replacing the interior
//!   child of largest surface area by that child's two children while it has fewer than eight;
//!   binary leaves stay leaves.
//! - [`Collapse::Sah`]: the surface-area cost of the 8-wide tree is minimised over all ways of
//!   cutting the binary tree into 8-wide nodes and leaves (dynamic programming over the binary
//!   nodes, as Ylitie, Karras and Laine 2017 do for compressed wide BVHs): a binary subtree of at
//!   most `max_leaf` primitives may become one leaf (its primitives are a contiguous range of the
//!   build order), so nodes fill up instead of ending in a few small leaves. Cost of a node:
//!   `area * node_cost`; of a leaf: `area * blocks * block_cost` (blocks of four triangles).
//!
//! Both are deterministic functions of the binary tree (ties go to the first candidate).
use super::wide_node::Bvh8Node;
use super::Bvh;
use alloc::vec;
use alloc::vec::Vec;

/// How binary nodes are grouped into 8-wide nodes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Collapse {
    /// Open the largest interior child until eight (the first 8-wide collapse).
    Greedy,
    /// Minimum surface-area cost.
    Sah {
        /// Cost of visiting a node (one eight-box test).
        node_cost: f32,
        /// Cost of testing one block of four triangles.
        block_cost: f32,
        /// Largest binary subtree (in primitives) that may become one leaf; binary leaves stay
        /// leaves whatever their size.
        max_leaf: usize,
    },
}

impl Collapse {
    /// The collapse scenes use. Measured with the Embree bench (`BVH8_COLLAPSE` overrides it
    /// there): see `docs/design/ray-casting.md`.
    pub const DEFAULT: Collapse = Collapse::Sah {
        node_cost: 2.0,
        block_cost: 1.0,
        max_leaf: 8,
    };

    /// Collapses `bin` (not empty); returns the nodes (root first) and the depth.
    pub(super) fn run(self, bin: &Bvh) -> (Vec<Bvh8Node>, usize) {
        let mut nodes = Vec::with_capacity(bin.nodes.len() / 7 + 1);
        let mut depth = 0;
        match self {
            Collapse::Greedy => {
                greedy(bin, 0, 1, &mut depth, &mut nodes);
            }
            Collapse::Sah {
                node_cost,
                block_cost,
                max_leaf,
            } => {
                let sah = Sah::new(bin, node_cost, block_cost, max_leaf);
                sah.emit(0, 1, &mut depth, &mut nodes);
            }
        }
        (nodes, depth)
    }
}

/// Writes node `me`'s lane for binary node `c`: a leaf (its primitive range) or a node index.
fn set_lane(nodes: &mut [Bvh8Node], me: usize, lane: usize, bin: &Bvh, c: usize, child: u32) {
    let node = &mut nodes[me];
    node.set_box(lane, bin.nodes[c].bounds);
    node.child[lane] = child;
    node.used |= 1 << lane;
}

/// The binary nodes that become the children of the 8-wide node made from binary node `at`
/// in the greedy collapse, and how many there are (at most eight): its two children, then,
/// while fewer than eight, the interior child of largest surface area replaced by its own two
/// children (the first of equal areas). A leaf stays a single child.
fn greedy_children(bin: &Bvh, at: usize) -> ([usize; 8], usize) {
    const W: usize = 8;
    let n = &bin.nodes[at];
    let mut kids = [at; W];
    let mut k = 1;
    if n.count == 0 {
        kids[0] = at + 1;
        kids[1] = n.offset as usize;
        k = 2;
        while k < W {
            let mut best: Option<(usize, f32)> = None;
            for (j, &c) in kids[..k].iter().enumerate() {
                let cn = &bin.nodes[c];
                if cn.count == 0 && best.is_none_or(|(_, a)| cn.bounds.area() > a) {
                    best = Some((j, cn.bounds.area()));
                }
            }
            let Some((j, _)) = best else { break };
            let c = kids[j];
            kids[j] = c + 1;
            kids[k] = bin.nodes[c].offset as usize;
            k += 1;
        }
    }
    (kids, k)
}

fn greedy(
    bin: &Bvh,
    at: usize,
    depth: usize,
    max_depth: &mut usize,
    nodes: &mut Vec<Bvh8Node>,
) -> u32 {
    *max_depth = (*max_depth).max(depth);
    let (kids, k) = greedy_children(bin, at);
    let me = nodes.len();
    nodes.push(Bvh8Node::EMPTY);
    for (lane, &c) in kids[..k].iter().enumerate() {
        let cn = &bin.nodes[c];
        let child = if cn.count > 0 {
            nodes[me].count[lane] = cn.count;
            nodes[me].leaves |= 1 << lane;
            cn.offset
        } else {
            greedy(bin, c, depth + 1, max_depth, nodes)
        };
        set_lane(nodes, me, lane, bin, c, child);
    }
    me as u32
}

/// The dynamic program's table: `cost[n][j - 1]` is the least cost of binary subtree `n` cut
/// into at most `j` children of a wide node; `first[n]` and `prims[n]` its primitive range.
struct Sah<'a> {
    bin: &'a Bvh,
    cost: Vec<[f32; 8]>,
    /// Whether the one-child form of `n` is a leaf (else an 8-wide node).
    leaf: Vec<bool>,
    first: Vec<u32>,
    prims: Vec<u32>,
}

impl<'a> Sah<'a> {
    fn new(bin: &'a Bvh, node_cost: f32, block_cost: f32, max_leaf: usize) -> Sah<'a> {
        let n = bin.nodes.len();
        let mut s = Sah {
            bin,
            cost: vec![[0.0; 8]; n],
            leaf: vec![false; n],
            first: vec![0; n],
            prims: vec![0; n],
        };
        // Children have larger indices than their parent (depth-first order).
        for i in (0..n).rev() {
            let node = &bin.nodes[i];
            let area = node.bounds.area();
            if node.count > 0 {
                s.first[i] = node.offset;
                s.prims[i] = u32::from(node.count);
                let c = area * block_cost * node.count.div_ceil(4) as f32;
                s.cost[i] = [c; 8];
                s.leaf[i] = true;
                continue;
            }
            let (l, r) = (i + 1, node.offset as usize);
            s.first[i] = s.first[l];
            s.prims[i] = s.prims[l] + s.prims[r];
            let as_node = area * node_cost + s.split(i, 8).0;
            let count = s.prims[i] as usize;
            let as_leaf = if count <= max_leaf {
                area * block_cost * count.div_ceil(4) as f32
            } else {
                f32::INFINITY
            };
            s.leaf[i] = as_leaf <= as_node;
            let mut best = as_leaf.min(as_node);
            s.cost[i][0] = best;
            for j in 2..=8 {
                best = best.min(s.split(i, j).0);
                s.cost[i][j - 1] = best;
            }
        }
        s
    }

    /// Least cost of interior node `i`'s two children sharing at most `j >= 2` slots, and how
    /// many the first child gets.
    fn split(&self, i: usize, j: usize) -> (f32, usize) {
        let (l, r) = (i + 1, self.bin.nodes[i].offset as usize);
        let mut best = (f32::INFINITY, 1);
        for k in 1..j {
            let c = self.cost[l][k - 1] + self.cost[r][j - k - 1];
            if c < best.0 {
                best = (c, k);
            }
        }
        best
    }

    /// The binary nodes that become the children when subtree `i` gets at most `j` slots.
    fn children(&self, i: usize, j: usize, out: &mut Vec<usize>) {
        let node = &self.bin.nodes[i];
        // One child unless splitting into more is strictly cheaper (as the table was built).
        if node.count > 0 || j == 1 || self.cost[i][j - 1] == self.cost[i][0] {
            out.push(i);
            return;
        }
        // The smallest slot count reaching this cost, then its best split.
        let mut jj = j;
        while jj > 2 && self.cost[i][jj - 2] == self.cost[i][j - 1] {
            jj -= 1;
        }
        let (_, k) = self.split(i, jj);
        self.children(i + 1, k, out);
        self.children(node.offset as usize, jj - k, out);
    }

    /// Writes the 8-wide node for binary interior node `i` (or, for a binary leaf at the root,
    /// a node holding it) and its subtree; returns its index.
    fn emit(
        &self,
        i: usize,
        depth: usize,
        max_depth: &mut usize,
        nodes: &mut Vec<Bvh8Node>,
    ) -> u32 {
        *max_depth = (*max_depth).max(depth);
        let mut kids = Vec::with_capacity(8);
        if self.bin.nodes[i].count > 0 {
            kids.push(i);
        } else {
            let (_, k) = self.split(i, 8);
            self.children(i + 1, k, &mut kids);
            self.children(self.bin.nodes[i].offset as usize, 8 - k, &mut kids);
        }
        let me = nodes.len();
        nodes.push(Bvh8Node::EMPTY);
        for (lane, &c) in kids.iter().enumerate() {
            let child = if self.leaf[c] {
                nodes[me].count[lane] = self.prims[c] as u16;
                nodes[me].leaves |= 1 << lane;
                self.first[c]
            } else {
                self.emit(c, depth + 1, max_depth, nodes)
            };
            set_lane(nodes, me, lane, self.bin, c, child);
        }
        me as u32
    }
}

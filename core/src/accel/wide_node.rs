//! The 8-wide hierarchy's node: eight child boxes in SoA layout, tested at once by the slab
//! test, and per child its node or leaf. Its own file because both the collapse, which fills
//! nodes, and the tree with its walk, which reads them, use it (and the tree uses the collapse).
use super::slab::{MAX_X, MIN_X};
use super::slab_simd::Boxes8;
use crate::math::Aabb;
use glam::Vec3;

/// A node: eight child boxes, and per child its node index (`count == 0`) or its leaf's first
/// primitive and primitive count. 256 bytes, four cache lines.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub struct Bvh8Node {
    /// The children's boxes; unused lanes hold the empty box.
    pub boxes: Boxes8,
    /// Interior child: its node index. Leaf: its first primitive. Unused: `u32::MAX`.
    pub child: [u32; 8],
    /// Leaf: number of primitives (at least 1). Interior or unused: 0.
    pub count: [u16; 8],
    /// Bit `i` set when lane `i` is used (used lanes come first).
    pub used: u32,
    /// Bit `i` set when lane `i` is a leaf.
    pub leaves: u32,
}

// Four cache lines, as the memory figures assume.
const _: () = assert!(core::mem::size_of::<Bvh8Node>() == 256);
// The boxes are the first three lines (what the traversal prefetches of a child node).
const _: () =
    assert!(core::mem::offset_of!(Bvh8Node, boxes) == 0 && core::mem::size_of::<Boxes8>() == 192);

impl Bvh8Node {
    pub(super) const EMPTY: Bvh8Node = Bvh8Node {
        boxes: Boxes8::EMPTY,
        child: [u32::MAX; 8],
        count: [0; 8],
        used: 0,
        leaves: 0,
    };

    pub(super) fn set_box(&mut self, lane: usize, b: Aabb) {
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

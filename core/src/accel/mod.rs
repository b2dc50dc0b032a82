//! Acceleration structures: the binary SAH BVH (built first), the 8-wide BVH collapsed from it,
//! which scenes traverse with SIMD box tests, and its leaves' blocks of four triangles, tested
//! with SIMD too.
//!
//! Files, each named for its role:
//! - `binary`: the binary hierarchy built with the binned surface-area heuristic;
//! - `fork`: how a caller lends threads to that build;
//! - `collapse`: collapsing it into 8-wide nodes;
//! - `wide_node`: the 8-wide node (eight child boxes and their children);
//! - `wide`: the 8-wide hierarchy scenes cast rays with, and its walk (`entry`: the walk's stack
//!   order; `root`: the walk of a one-node tree; `leaves`: what the walk calls at a leaf);
//! - `slab`: the ray-box slab test's common ground (the prepared ray, the box layout, the
//!   portable reference);
//! - `slab_simd`: eight slab tests at once with SSE or AVX2, and the AVX2 token that picks the
//!   kernels a walk compiles with (`unsafe`, fenced);
//! - `tri_block`: a block of four triangles and its four-lane watertight test (`unsafe`, fenced);
//! - `tri_block_pair`: two blocks tested in one AVX2 pass (`unsafe`, fenced);
//! - `blocks`: packing leaves into triangle blocks, and the leaf loops over them;
//! - `counts`: the casts that count their work;
//! - `level`: one level of primitives, blocks and hierarchy (the scene's top level, or a shape
//!   group's bottom level under instances).
mod binary;
mod blocks;
mod collapse;
mod counts;
mod entry;
mod fork;
mod leaves;
pub mod level;
mod root;
pub mod slab;
pub mod slab_simd;
pub mod tri_block;
pub mod tri_block_pair;
mod wide;
mod wide_node;
pub use binary::{BuildParams, Bvh, BvhNode};
pub use blocks::{AnyLeaves, ClosestLeaves, LeafRanges, TriBlocks};
pub use collapse::Collapse;
pub use counts::TraversalCounts;
pub use fork::{Fork, InTurn};
pub use leaves::Leaves;
pub use wide::Bvh8;
pub use wide_node::Bvh8Node;

//! Acceleration structures: the binary SAH BVH (built first), the 8-wide BVH collapsed from it,
//! which scenes traverse with SIMD box tests, and its leaves' blocks of four triangles, tested
//! with SIMD too.
mod blocks;
mod bvh;
mod bvh8;
mod collapse;
mod counts;
mod entry;
mod leaves;
mod root;
pub mod simd;
pub mod simd8;
pub mod tri4;
pub mod tri8;
pub use blocks::{AnyLeaves, ClosestLeaves, LeafRanges, TriBlocks};
pub use bvh::{BuildParams, Bvh, BvhNode};
pub use bvh8::{Bvh8, Bvh8Node};
pub use collapse::Collapse;
pub use counts::TraversalCounts;
pub use leaves::Leaves;

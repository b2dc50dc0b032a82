//! Acceleration structures: the binary SAH BVH (built first), the 4-wide BVH collapsed from
//! it, which scenes traverse with SIMD box tests, and its leaves' blocks of four triangles,
//! tested with SIMD too.
mod blocks;
mod bvh;
mod bvh4;
mod counts;
pub mod simd;
pub mod tri4;
pub use blocks::TriBlocks;
pub use bvh::{BuildParams, Bvh, BvhNode};
pub use bvh4::{Bvh4, Bvh4Node};
pub use counts::TraversalCounts;

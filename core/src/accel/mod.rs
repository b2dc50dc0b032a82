//! Acceleration structures: the binary SAH BVH (built first), the 4- and 8-wide BVHs collapsed
//! from it, which scenes traverse with SIMD box tests, and their leaves' blocks of four
//! triangles, tested with SIMD too.
mod blocks;
mod bvh;
mod bvh4;
mod bvh8;
mod collapse;
mod counts;
mod leaves;
mod root;
pub mod simd;
pub mod simd8;
pub mod tri4;
pub mod tri8;
pub use blocks::{AnyLeaves, ClosestLeaves, LeafRanges, TriBlocks};
pub use bvh::{BuildParams, Bvh, BvhNode};
pub use bvh4::{Bvh4, Bvh4Node};
pub use bvh8::{Bvh8, Bvh8Node};
pub use collapse::Collapse;
pub use counts::TraversalCounts;
pub use leaves::Leaves;

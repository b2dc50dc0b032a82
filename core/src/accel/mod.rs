//! Acceleration structures: the binary SAH BVH (built first) and the 4-wide BVH collapsed from
//! it, which scenes traverse with SIMD box tests.
mod bvh;
mod bvh4;
pub mod simd;
pub use bvh::{BuildParams, Bvh, BvhNode};
pub use bvh4::{Bvh4, Bvh4Node};

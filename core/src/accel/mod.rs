//! Acceleration structures.
mod bvh;
pub use bvh::{Bvh, BvhNode};

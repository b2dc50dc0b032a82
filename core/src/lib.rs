//! Tessera core: the `no_std` heart of the path tracer.
//!
//! Geometry, sampling, BSDFs, emitters, the camera and the per-sample `trace_path`
//! ([`integrator::Integrator::li`]). Everything here is allocation-free per sample, has no global
//! state and never panics on data: a non-finite sample is reported to the caller, who drops it.
//! Math goes through `glam` with the `libm` backend, so every build computes the same bits;
//! square roots, lengths and normalisations go through [`math::sqrt`] and [`math::Norm`] (the same
//! bits as libm's and glam's, without libm's legacy-SSE assembly).
#![no_std]
// `unsafe` only in `accel::slab_simd`, `accel::tri_block`, `accel::tri_block_pair` (SSE/AVX2
// intrinsics, CPU feature detection) and `math::sqrt` (the SSE square-root intrinsics), which
// allow it and justify each block.
#![deny(unsafe_code)]
// `!(x > 0.0)` is this crate's way of rejecting NaN along with the values it names; clippy's
// suggestion (`partial_cmp`) would hide that intent.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

extern crate alloc;

pub mod accel;
pub mod adaptive;
pub mod bsdf;
pub mod camera;
pub mod emitter;
pub mod error_estimate;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod light;
pub mod math;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod texture;

pub use glam;

/// Linear RGB radiance, reflectance or throughput.
pub type Color = glam::Vec3;

//! Tessera core: the `no_std` heart of the path tracer.
//!
//! Geometry, sampling, BSDFs, emitters, the camera and the per-sample `trace_path`
//! ([`integrator::Integrator::li`]). Everything here is allocation-free per sample, has no global
//! state and never panics on data: a non-finite sample is reported to the caller, who drops it.
//! Math goes through `glam` with the `libm` backend, so every build computes the same bits;
//! square roots, lengths and normalisations go through [`math::sqrt`] and [`math::Norm`] (the same
//! bits as libm's and glam's, without libm's legacy-SSE assembly).
//!
//! # Example
//!
//! A white furnace built in code: a diffuse sphere of albedo 0.5 under a sky of radiance 1
//! reflects exactly 0.5 toward the camera, so the centre pixel converges to 0.5 (the same scene,
//! with a corner pixel, is `core/examples/furnace.rs`).
//!
//! ```
//! use tessera_core::bsdf::{Bsdf, Diffuse};
//! use tessera_core::camera::{Camera, Filter, FovAxis};
//! use tessera_core::emitter::{ConstantEnv, Emitter};
//! use tessera_core::film::PixelAccum;
//! use tessera_core::geometry::{Shape, ShapeKind, Sphere};
//! use tessera_core::glam::{Mat4, Vec3};
//! use tessera_core::integrator::{Integrator, PathIntegrator};
//! use tessera_core::light::LightSelection;
//! use tessera_core::math::Transform;
//! use tessera_core::render::RenderJob;
//! use tessera_core::scene::{Scene, SceneParts};
//! use tessera_core::texture::Texture;
//! use tessera_core::Color;
//!
//! // A camera at z = 4 looking down -z (it looks along its local +z).
//! let to_world = Transform::new(Mat4::from_translation(Vec3::new(0.0, 0.0, 4.0))
//!     * Mat4::from_rotation_y(core::f32::consts::PI)).unwrap();
//! let camera = Camera::perspective(to_world, 16, 16, 30.0, FovAxis::X, 0.01, 1e4);
//! let sphere = Shape {
//!     kind: ShapeKind::Sphere(Sphere { center: Vec3::ZERO, radius: 1.0 }),
//!     bsdf: 0,
//!     emitter: None,
//!     flip_normals: false,
//! };
//! let scene = Scene::new(SceneParts {
//!     shapes: vec![sphere],
//!     disks: Vec::new(),
//!     bsdfs: vec![Bsdf::Diffuse(Diffuse { reflectance: Texture::Constant(Color::splat(0.5)) })],
//!     emitters: vec![Emitter::Constant(ConstantEnv { radiance: Color::ONE })],
//!     camera,
//!     filter: Filter::Box,
//!     light_selection: LightSelection::Power,
//!     groups: Vec::new(),
//!     instances: Vec::new(),
//! })
//! .unwrap();
//! let integrator = Integrator::Path(PathIntegrator::default());
//! let job = RenderJob::new(&scene, &integrator, 7);
//! let mut pixel = PixelAccum::default();
//! job.accumulate(8, 8, 0..1024, &mut pixel);
//! let green = pixel.mean()[1];
//! assert!((green - 0.5).abs() < 0.02, "{green}");
//! ```
#![no_std]
// `unsafe` only in `accel::slab_simd`, `accel::tri_block`, `accel::tri_block_pair` (SSE/AVX2
// intrinsics, CPU feature detection), `emitter::envmap_coords` (AVX2 intrinsics) and
// `math::sqrt` (the SSE square-root intrinsics), which allow it and justify each block.
#![deny(unsafe_code)]
// `!(x > 0.0)` is this crate's way of rejecting NaN along with the values it names; clippy's
// suggestion (`partial_cmp`) would hide that intent.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]

extern crate alloc;

pub mod accel;
pub mod adaptive;
pub mod bsdf;
pub mod camera;
mod camera_batch;
mod camera_draw;
pub mod emitter;
pub mod error_estimate;
mod escapes;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod light;
pub mod math;
pub mod medium;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod splat;
pub mod texture;

pub use glam;

/// Linear RGB radiance, reflectance or throughput.
pub type Color = glam::Vec3;

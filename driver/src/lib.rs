//! Tessera's driver: scene files, threaded tile rendering, images, the command line, and the
//! statistics harness. As a library, start from [`load`] / [`load_str`] and [`render`]; see
//! `driver/examples/render_scene.rs`.
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
mod api;
pub mod bench;
pub mod checkpoint;
pub mod cli;
pub mod compare;
pub mod debug_pixel;
pub mod error;
pub mod image_io;
pub mod mesh;
pub mod overlay;
pub mod progressive;
pub mod render;
mod render_groups;
pub mod render_stats;
pub mod scene;
pub mod split;
pub mod stats;
pub mod testfile;
pub mod xml;

pub use api::{load, load_str, render, Image, Options};

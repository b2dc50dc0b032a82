//! Tessera's driver: threaded tile rendering of a loaded scene, passes and time budgets,
//! checkpoints, splitting a render over processes, image output and overlays. Scenes are loaded
//! by `tessera-scene`; as a library, start from [`load`] / [`load_str`] and [`render`](fn@render); see
//! `driver/examples/render_scene.rs`.
//!
//! # Example
//!
//! ```
//! let xml = r#"<scene version="3.0.0">
//!     <sensor type="perspective">
//!         <float name="fov" value="45"/>
//!         <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/></film>
//!     </sensor>
//!     <shape type="sphere"><bsdf type="diffuse"/></shape>
//!     <emitter type="constant"/>
//! </scene>"#;
//! let scene = tessera::load_str(xml, ".").unwrap();
//! let one = tessera::Options { spp: Some(8), threads: Some(1), ..Default::default() };
//! let two = tessera::Options { threads: Some(2), tile_size: 5, ..one.clone() };
//! let image = tessera::render(&scene, &one);
//! assert_eq!((image.width, image.height), (24, 16));
//! // The same bits whatever the threads and tiles.
//! assert_eq!(image.data, tessera::render(&scene, &two).data);
//! ```
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]
mod api;
pub mod checkpoint;
mod exr_blocks;
pub mod framebuffer;
pub mod image_io;
pub mod layers;
pub mod overlay;
pub mod progressive;
pub mod render;
mod render_groups;
pub mod render_stats;
pub mod splats;
pub mod split;
pub mod text;
pub mod tile;
mod tile_sums;

pub use api::{load, load_str, render, Image, Options};
pub use tessera_scene::error::InputError;
pub use tessera_scene::LoadedScene;

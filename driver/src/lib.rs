//! Tessera's driver: threaded tile rendering of a loaded scene, passes and time budgets,
//! checkpoints, splitting a render over processes, image output and overlays. Scenes are loaded
//! by `tessera-scene`; as a library, start from [`load`] / [`load_str`] and [`render`](fn@render); see
//! `driver/examples/render_scene.rs`.
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
mod api;
pub mod checkpoint;
pub mod image_io;
pub mod layers;
pub mod overlay;
pub mod progressive;
pub mod render;
mod render_groups;
pub mod render_stats;
pub mod split;
pub mod text;
pub mod tile;

pub use api::{load, load_str, render, Image, Options};
pub use tessera_scene::error::InputError;
pub use tessera_scene::LoadedScene;

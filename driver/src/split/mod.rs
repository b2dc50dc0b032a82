//! Splitting a render across processes or machines and putting it back together.
//!
//! A render restricted to a crop window, a tile set or a sample range (see [`selection`]) writes
//! a *part* ([`part`]): an EXR with the window's mean RGB (so it can be viewed) plus every
//! pixel's exact f64 sums and counts and the settings that made it. [`merge`] checks that parts
//! belong together and assembles them: spatial parts by copying pixels (bit-identical to one
//! whole render), sample-range parts by adding sums in order of range start.
pub mod merge;
pub mod part;
pub mod selection;

pub use part::{read_part, write_part, Part, PartInfo};
pub use selection::PixelSelection;

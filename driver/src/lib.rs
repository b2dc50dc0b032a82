pub mod cli;
pub mod error;
pub mod image_io;
pub mod mesh;
pub mod render;
pub mod scene;
pub mod stats;
pub mod xml;

//! Sensors and pixel reconstruction filters.
mod filter;
mod perspective;

pub use filter::{Filter, GaussianFilter};
pub use perspective::{FovAxis, Perspective};

//! Sensors and pixel reconstruction filters.
mod filter;
mod perspective;
mod step_profile;

pub use filter::{Filter, GaussianFilter, TentFilter};
pub use perspective::{FovAxis, Perspective};
pub use step_profile::{StepProfile, STEPS};

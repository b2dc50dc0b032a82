//! Sensors and pixel reconstruction filters.
mod filter;
mod negative_lobes;
mod perspective;
mod signed_profile;
mod step_profile;

pub use filter::{Filter, GaussianFilter, TentFilter};
pub use negative_lobes::{LanczosFilter, MitchellFilter};
pub use perspective::{FovAxis, Perspective};
pub use signed_profile::SignedProfile;
pub use step_profile::{StepProfile, STEPS};

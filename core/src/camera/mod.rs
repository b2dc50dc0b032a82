//! Sensors and pixel reconstruction filters.
mod differentials;
mod filter;
mod filter_table;
mod negative_lobes;
mod orthographic;
mod perspective;
mod sensor;
mod signed_profile;
mod step_profile;
mod thin_lens;

pub use differentials::Differentials;
pub use filter::{Filter, GaussianFilter, TentFilter};
pub use filter_table::FilterTable;
pub use negative_lobes::{LanczosFilter, MitchellFilter};
pub use orthographic::Orthographic;
pub use perspective::{FovAxis, Perspective};
pub use sensor::{Camera, Crop, Projection};
pub use signed_profile::SignedProfile;
pub use step_profile::{StepProfile, STEPS};
pub use thin_lens::ThinLens;

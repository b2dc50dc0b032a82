//! Light transport's side of the lights: which light a shadow ray goes to, what each light is
//! expected to give a point, where a light cannot reach, and the two ways an integrator finds
//! light (sampling an emitter, or reading what a BSDF-sampled ray ran into).
//!
//! The emitters themselves (what each kind of light emits and how it is sampled from a point)
//! are in `emitter`; this module decides among them and connects them to the integrators:
//! - `sampler`: the scene's light sampler, built once from its emitters (by power, uniform, or
//!   per vertex), and the `light_selection` setting that chooses among these;
//! - `vertex`: the per-vertex choice, weighing each light's estimate by the BSDF toward it;
//! - `light_lanes`: the same weighing four lights at a time, in a vector's lanes;
//! - `bound`: each light as that choice sees it, and its estimate at a point;
//! - `behind`: the half-space behind a flat one-sided light, where its sampling is skipped;
//! - `sample`: what one emitter sample delivers to an integrator;
//! - `strategies`: emitter sampling from a surface point, and emission along a traced ray.
mod behind;
mod bound;
mod light_lanes;
mod sample;
mod sampler;
mod strategies;
mod vertex;

pub use behind::Behind;
pub use bound::{LightBound, LightEstimate};
pub use light_lanes::LightLanes;
pub use sample::LightSample;
pub use sampler::{LightSampler, LightSelection};
pub(crate) use strategies::emission_along;
pub use strategies::sample_light;
pub use vertex::{VertexSelection, MAX_VERTEX_LIGHTS, UNIFORM_SHARE};

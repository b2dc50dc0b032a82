//! Random numbers and warping functions.
mod discrete;
mod distribution2d;
mod independent;
mod kind;
mod layout;
pub mod owen;
pub mod sobol;
pub mod warp;
pub mod zsobol;
mod zsobol_lanes;
mod zsobol_pixel;

pub use discrete::Discrete1D;
pub use distribution2d::Distribution2D;
pub use independent::IndependentSampler;
pub use kind::{SamplerKind, SAMPLER_NAMES};
pub use layout::{
    dimension_of, paired_dimension, Stage, BOUNCE_DIMENSIONS, CAMERA_DIMENSIONS, LENS_DIMENSION,
};
pub use zsobol::{ZSobolSampler, CACHED_DIMENSIONS, MAX_LOG2_SPP};
pub use zsobol_pixel::{CachedZSobol, ZSobolPixel};

use glam::Vec2;

/// A source of sample values in `[0, 1)`. Implementations are deterministic functions of how they
/// were created; the integrators draw from them in a fixed order.
pub trait Sampler {
    /// One value in `[0, 1)`.
    fn next_1d(&mut self) -> f32;
    /// Two values in `[0, 1)^2`.
    fn next_2d(&mut self) -> Vec2 {
        let x = self.next_1d();
        let y = self.next_1d();
        Vec2::new(x, y)
    }
    /// Moves past one dimension without using it: the state `next_1d` would leave, at no more
    /// cost (samplers that address dimensions directly only advance the dimension).
    #[inline]
    fn skip_1d(&mut self) {
        let _ = self.next_1d();
    }
    /// Makes the next draw read dimension `dim`, for samplers whose dimensions are stratified
    /// across a pixel's samples (see [`layout`](self::dimension_of)). Samplers whose draws are
    /// independent of each other ignore it (the default), so their streams do not move.
    #[inline]
    fn start_dimension(&mut self, dim: u32) {
        let _ = dim;
    }
    /// Makes the next draw read the first dimension of `stage` of bounce `depth`:
    /// `start_dimension(dimension_of(depth, stage))`.
    #[inline]
    fn start_stage(&mut self, depth: u32, stage: Stage) {
        self.start_dimension(dimension_of(depth, stage));
    }
}

//! A sample's camera part, drawn before its path is followed: the render loops draw the camera
//! rays of a few samples together ([`CAMERA_BATCH`]) and then finish them.
use crate::math::Ray;
use crate::Color;
use glam::Vec2;

/// How many samples of a pixel have their camera rays made together (`RenderJob::pixel_alone`).
pub(crate) const CAMERA_BATCH: usize = 8;

/// A sample's camera part: the sampler (to go on drawing from), the film position, the offset
/// from the pixel's centre and the camera sample.
pub(crate) struct CameraDraw<S> {
    pub(crate) sampler: S,
    pub(crate) pos: Vec2,
    pub(crate) offset: Vec2,
    pub(crate) cam: CameraSample,
}

/// A sample's camera ray and the weight its value is multiplied by (filters with negative
/// lobes, importance-sampled: the sign and size of the filter there; `None` for the others).
#[derive(Clone, Copy, Debug)]
pub struct CameraSample {
    /// The camera ray.
    pub ray: Ray,
    /// The filter's weight, if the value is weighted.
    pub weight: Option<f32>,
}

impl CameraSample {
    /// A value of this sample as the render loop records it: times the weight, if any.
    #[inline]
    pub fn weigh(&self, v: Color) -> Color {
        self.weight.map_or(v, |w| v * w)
    }
}

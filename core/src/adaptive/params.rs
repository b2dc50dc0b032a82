//! The settings of adaptive sampling, and how many times the mean sample count an adaptive
//! render's `zsobol` pixel blocks hold.
use crate::integrator::{Integrator, GROUP_H, GROUP_W};

/// How many times the mean sample count an adaptive render's `zsobol` pixel blocks hold
/// (`tessera render --adaptive` sets the sampler up for this many times the scene's sample
/// count). Noisy pixels take several times the mean (cbox at a mean of 64: 23 to 325), and
/// samples past a pixel's block start a fresh randomisation instead of continuing its
/// stratified sequence. Measured at a mean of 64 spp (128x128, 4 seeds): blocks of 1024 instead
/// of 64 lowered relMSE from 7.28e-5 to 6.52e-5 on veach_mis and from 2.09e-3 to 2.00e-3 on cbox.
/// With the Gaussian filter (512 wide, mean 64 spp, three seeds, relMSE less the references'
/// noise) blocks of 64 instead were mixed: the bunny 9% and cbox 2.5% lower, the material
/// scene equal, veach_mis 6% higher; 16 is kept.
pub const ZSOBOL_BLOCK_FACTOR: u64 = 16;

/// Settings of adaptive sampling's pass planning (`adaptive::plan_pass`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveParams {
    /// Added to `mean^2` in the relative variance (default 0.01).
    pub floor: f64,
    /// Share of all samples spread evenly over the pixels, in `[0, 1]` (default 0.25).
    pub uniform: f64,
    /// Samples every pixel takes before the first adaptive pass (at least 1; default 1: a
    /// pixel holding one sample is judged by its neighbourhood, see
    /// [`neighbourhood_variance`](super::variance::neighbourhood_variance)).
    pub warmup: u64,
    /// Width and height of the aligned blocks of pixels that are planned together and take the
    /// same count in each pass (default `(1, 1)`: every pixel on its own). The reuse group's
    /// size when the integrator shares light among groups of pixels (path reuse), which then
    /// finds every pixel of a group at each sample index instead of tracing the others' paths
    /// only to share them ([`AdaptiveParams::for_integrator`]).
    pub block: (u32, u32),
    /// How samples are priced: `Some(k)`, a pixel's sample costs the rays its samples cast on
    /// average ([`PixelAccum::rays`](crate::film::PixelAccum::rays)) plus `k` rays' worth of
    /// fixed work (drawing the camera ray, adding the value), `k` at least 0, and the plan
    /// makes the most of a fixed cost (default `Some(1.0)`); `None`, every sample costs the
    /// same. (A plan whose scores are not finite shares the samples evenly.)
    pub sample_cost: Option<f64>,
}

impl Default for AdaptiveParams {
    fn default() -> Self {
        AdaptiveParams {
            floor: 0.01,
            uniform: 0.25,
            warmup: 1,
            block: (1, 1),
            sample_cost: Some(1.0),
        }
    }
}

impl AdaptiveParams {
    /// These settings for rendering with `integrator`: blocks of its reuse groups
    /// ([`GROUP_W`] x [`GROUP_H`]) when it shares light among them ([`crate::render::reuses`]),
    /// so that each pass finds every pixel of a group at each sample index.
    pub fn for_integrator(self, integrator: &Integrator) -> Self {
        if !crate::render::reuses(integrator) {
            return self;
        }
        AdaptiveParams {
            block: (GROUP_W, GROUP_H),
            ..self
        }
    }
}

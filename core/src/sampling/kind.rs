//! Which sampler renders a scene: a closed enum, chosen by the scene file or the command line
//! and stored in the `Scene`; `render::RenderJob` dispatches on it.
use super::zsobol::log2_spp_for;

/// The samplers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SamplerKind {
    /// Independent uniform values from a PCG32 stream per pixel and sample (the default of a
    /// core scene built in code; a file that names no sampler loads as `ZSobol`).
    #[default]
    Independent,
    /// Owen-scrambled Sobol points in Morton order; `log2_spp` is the pixel block size `K`
    /// (see [`ZSobolSampler`](super::ZSobolSampler)).
    ZSobol {
        /// `ceil(log2(samples per pixel))`, at most 32.
        log2_spp: u32,
    },
}

/// Names accepted by [`SamplerKind::from_name`], for messages.
pub const SAMPLER_NAMES: &str = "independent, zsobol";

impl SamplerKind {
    /// The sampler called `name` set up for `spp` samples per pixel, if the name is known.
    pub fn from_name(name: &str, spp: u64) -> Option<SamplerKind> {
        match name {
            "independent" => Some(SamplerKind::Independent),
            "zsobol" => Some(SamplerKind::ZSobol {
                log2_spp: log2_spp_for(spp),
            }),
            _ => None,
        }
    }

    /// The same sampler set up for `spp` samples per pixel.
    pub fn for_spp(self, spp: u64) -> SamplerKind {
        match self {
            SamplerKind::Independent => SamplerKind::Independent,
            SamplerKind::ZSobol { .. } => SamplerKind::ZSobol {
                log2_spp: log2_spp_for(spp),
            },
        }
    }

    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            SamplerKind::Independent => "independent",
            SamplerKind::ZSobol { .. } => "zsobol",
        }
    }
}

//! The framebuffer: every pixel's accumulated samples, their splatted sums when the scene
//! splats, and, when asked, the same samples' XYZ squares (a second moment) and surface
//! variables of their camera rays (`aov` outputs), gathered in the colour's pass.
use crate::splats::Splats;
use tessera_core::film::PixelAccum;
use tessera_core::integrator::AovIntegrator;
use tessera_core::render::RenderJob;
use tessera_core::splat::{stride, Footprint};

/// Accumulated samples of every pixel, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Each pixel's own samples: their sums and counts (what error estimates, adaptive
    /// sampling and statistical tests read).
    pub pixels: Vec<PixelAccum>,
    /// When the scene splats its samples, each pixel's sums for the pixels its samples reach
    /// (see `core/src/splat.rs`): the image is made from these.
    pub splats: Option<Splats>,
    /// When asked for ([`Framebuffer::with_squares`]), the same samples' XYZ squared
    /// ([`xyz_squared`](tessera_core::integrator::xyz_squared)), summed and splatted exactly as the colour is: the second moment of
    /// Mitsuba 3's `moment` integrator, taken in the colour's own pass rather than by rendering
    /// every sample again. Its pixel means are the bits a render of that integrator gives.
    /// Checkpoints and part files do not carry it (renders that write them do not gather it).
    pub squares: Option<Box<Framebuffer>>,
    /// When asked for ([`Framebuffer::with_aovs`]), surface variables of the same samples'
    /// camera rays, each summed and splatted exactly as the colour is (with the filter's
    /// weight where samples carry one): the pixel means are the bits a render of each
    /// variable's integrator gives, without rendering the samples again. Checkpoints and part
    /// files do not carry them.
    pub aovs: Vec<GatheredAov>,
}

/// A surface variable gathered beside the colour: its integrator and its sums.
#[derive(Clone, Debug, PartialEq)]
pub struct GatheredAov {
    /// The variable (with the render's sample count, which its differentials depend on).
    pub aov: AovIntegrator,
    /// Its sums, shaped as the colour's.
    pub fb: Framebuffer,
}

impl Framebuffer {
    /// An empty buffer whose image is its pixels' means (samples that do not splat).
    pub fn new(width: u32, height: u32) -> Self {
        Framebuffer::with_footprint(width, height, None)
    }
    /// An empty buffer whose samples splat over `footprint` (or, without one, count in their
    /// own pixel only).
    pub fn with_footprint(width: u32, height: u32, footprint: Option<&Footprint>) -> Self {
        Framebuffer::with_reach(width, height, footprint.map(Footprint::reach))
    }
    /// An empty buffer whose samples splat with reach `reach` (or, without one, count in their
    /// own pixel only).
    pub fn with_reach(width: u32, height: u32, reach: Option<u32>) -> Self {
        let n = width as usize * height as usize;
        Framebuffer {
            width,
            height,
            pixels: vec![PixelAccum::default(); n],
            splats: reach.map(|r| Splats::new(r, n)),
            squares: None,
            aovs: Vec::new(),
        }
    }
    /// This buffer, set to also gather its samples' XYZ squares ([`Framebuffer::squares`]),
    /// from the next sample on.
    pub fn with_squares(mut self) -> Self {
        let reach = self.splats.as_ref().map(|s| s.reach);
        self.squares = Some(Box::new(Framebuffer::with_reach(
            self.width,
            self.height,
            reach,
        )));
        self
    }
    /// This buffer, set to also gather the variables `aovs` of its samples' camera rays
    /// ([`Framebuffer::aovs`]), from the next sample on. Renders of an integrator that reuses
    /// paths cannot gather them (see `render_span`).
    pub fn with_aovs(mut self, aovs: impl IntoIterator<Item = AovIntegrator>) -> Self {
        let reach = self.splats.as_ref().map(|s| s.reach);
        self.aovs = aovs
            .into_iter()
            .map(|aov| GatheredAov {
                aov,
                fb: Framebuffer::with_reach(self.width, self.height, reach),
            })
            .collect();
        self
    }
    /// Bytes the accumulators and splatted sums of a buffer of `pixels` pixels take, splatting
    /// with reach `reach` (or not at all).
    pub fn bytes_for(pixels: usize, reach: Option<u32>) -> usize {
        let sums = reach.map_or(0, |r| stride(r) * std::mem::size_of::<f32>());
        pixels * (std::mem::size_of::<PixelAccum>() + sums)
    }
    /// An empty buffer for `job`: its image size, splatting as its scene does.
    pub fn for_job(job: &RenderJob) -> Self {
        let (w, h) = job.size();
        Framebuffer::with_footprint(w, h, job.scene.splat.as_ref())
    }
    /// The image: each pixel's splatted sums over their weights when the scene splats (each
    /// pixel's sums by its mean where the pixels' counts differ), else each pixel's mean.
    pub fn rgb(&self) -> Vec<[f32; 3]> {
        match &self.splats {
            Some(s) => {
                let samples: Vec<u64> = self.pixels.iter().map(|p| p.count + p.dropped).collect();
                s.resolve(self.width, self.height, &samples)
            }
            None => self.pixels.iter().map(|p| p.mean()).collect(),
        }
    }
    /// Samples dropped because they were not finite.
    pub fn dropped(&self) -> u64 {
        self.pixels.iter().map(|p| p.dropped).sum()
    }
    /// Accumulator of pixel `(x, y)`.
    pub fn at(&self, x: u32, y: u32) -> &PixelAccum {
        &self.pixels[y as usize * self.width as usize + x as usize]
    }
}

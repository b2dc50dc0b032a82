//! The per-sample entry point: one camera sample of one pixel, replayable alone.
use crate::film::PixelAccum;
use crate::integrator::{Integrator, NoProbe, Probe};
use crate::sampling::{IndependentSampler, Sampler, SamplerKind, ZSobolPixel, ZSobolSampler};
use crate::scene::Scene;
use crate::Color;
use core::ops::Range;
use glam::Vec2;

/// Radiance of sample `index` of pixel `(x, y)`: a pure function of its arguments (and of
/// `scene.sampler`, which picks the sampler).
#[inline]
pub fn render_sample(
    scene: &Scene,
    integrator: &Integrator,
    seed: u64,
    x: u32,
    y: u32,
    index: u64,
) -> Color {
    render_sample_probed(scene, integrator, seed, x, y, index, &mut NoProbe)
}

/// [`render_sample`], telling `probe` about the work done: the same value for any probe.
#[inline]
pub fn render_sample_probed<P: Probe>(
    scene: &Scene,
    integrator: &Integrator,
    seed: u64,
    x: u32,
    y: u32,
    index: u64,
    probe: &mut P,
) -> Color {
    match scene.sampler {
        SamplerKind::Independent => trace(
            scene,
            integrator,
            x,
            y,
            IndependentSampler::new(seed, x, y, index),
            probe,
        ),
        SamplerKind::ZSobol { log2_spp } => trace(
            scene,
            integrator,
            x,
            y,
            ZSobolSampler::new(seed, x, y, index, log2_spp),
            probe,
        ),
    }
}

/// Samples `samples` of pixel `(x, y)` in index order, each value passed to `add`: the values
/// of [`render_sample_probed`] for those indices, bit for bit, with the zsobol sampler's
/// per-pixel work done once for the pixel instead of once per sample ([`ZSobolPixel`]).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn render_samples_probed<P: Probe>(
    scene: &Scene,
    integrator: &Integrator,
    seed: u64,
    x: u32,
    y: u32,
    samples: Range<u64>,
    probe: &mut P,
    add: impl FnMut(Color),
) {
    let mut cache = PixelCache::default();
    render_samples_cached(
        scene, integrator, seed, x, y, samples, &mut cache, probe, add,
    );
}

/// What the pixels one worker renders one after another share: the zsobol sampler's table of
/// pixel parts (reused, not rebuilt, for each pixel) and its dimensions' hashes (the same for
/// every pixel). It holds no result: any cache gives the same values.
#[derive(Clone, Debug, Default)]
pub struct PixelCache {
    zsobol: Option<ZSobolPixel>,
}

/// [`render_samples_probed`] with a cache kept from pixel to pixel by the caller: the same
/// values, bit for bit, for any cache (fresh or used by other pixels, seeds or sample counts).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn render_samples_cached<P: Probe>(
    scene: &Scene,
    integrator: &Integrator,
    seed: u64,
    x: u32,
    y: u32,
    samples: Range<u64>,
    cache: &mut PixelCache,
    probe: &mut P,
    mut add: impl FnMut(Color),
) {
    match scene.sampler {
        SamplerKind::Independent => {
            for index in samples {
                let s = IndependentSampler::new(seed, x, y, index);
                add(trace(scene, integrator, x, y, s, probe));
            }
        }
        SamplerKind::ZSobol { log2_spp } => {
            if samples.is_empty() {
                return;
            }
            let pixel = match &mut cache.zsobol {
                Some(p) => {
                    p.move_to(seed, x, y, log2_spp);
                    p
                }
                none => none.insert(ZSobolPixel::new(seed, x, y, log2_spp)),
            };
            pixel.set_run(samples.clone());
            for index in samples {
                add(trace(scene, integrator, x, y, pixel.sampler(index), probe));
            }
        }
    }
}

/// One camera sample of pixel `(x, y)` drawn from `sampler`.
#[inline]
fn trace<S: Sampler, P: Probe>(
    scene: &Scene,
    integrator: &Integrator,
    x: u32,
    y: u32,
    mut sampler: S,
    probe: &mut P,
) -> Color {
    let offset = scene.filter.sample(sampler.next_2d());
    let pos = Vec2::new(x as f32 + 0.5 + offset.x, y as f32 + 0.5 + offset.y);
    let ray = scene.camera.generate_ray(pos);
    probe.camera(pos, &ray);
    integrator.li_probed(scene, ray, &mut sampler, probe)
}

/// Adds samples `samples` of pixel `(x, y)` to `acc`, in index order.
pub fn render_pixel(
    scene: &Scene,
    integrator: &Integrator,
    seed: u64,
    x: u32,
    y: u32,
    samples: Range<u64>,
    acc: &mut PixelAccum,
) {
    render_samples_probed(scene, integrator, seed, x, y, samples, &mut NoProbe, |c| {
        acc.add(c)
    });
}

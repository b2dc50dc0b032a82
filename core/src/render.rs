//! The render entry: [`RenderJob`], the one value every sample of a render is a function of.
//!
//! A job is built once from the scene (which holds the sampler kind), the integrator and the
//! seed. Every value it gives is a pure function of the job, the pixel and the sample index
//! (and, with path reuse, of which pixels of the pixel's group take that index), so any loop
//! over pixels and sample ranges, in any order and on any thread, gives the same bits.
use crate::camera_batch::CameraBatch;
pub use crate::camera_draw::CameraSample;
use crate::camera_draw::{CameraDraw, CAMERA_BATCH};
use crate::escapes::{Escapes, Pending};
use crate::film::PixelAccum;
use crate::integrator::{
    Integrator, NoProbe, PathIntegrator, Probe, Radiance, GROUP, GROUP_H, GROUP_W,
};
use crate::sampling::{IndependentSampler, Sampler, SamplerKind, ZSobolPixel};
use crate::scene::Scene;
use crate::Color;
use core::ops::Range;
use glam::Vec2;

/// What a render's samples depend on: the scene (geometry, camera, filter, sampler kind), the
/// integrator and the seed of every random stream. Cheap to copy.
#[derive(Clone, Copy, Debug)]
pub struct RenderJob<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The integrator.
    pub integrator: &'a Integrator,
    /// Seed of every random stream.
    pub seed: u64,
}

impl<'a> RenderJob<'a> {
    /// A job rendering `scene` with `integrator` from `seed`.
    ///
    /// # Panics
    /// If the scene's environment maps sample by MIS-compensated tables and `integrator` takes
    /// emitter samples it does not weigh by MIS
    /// ([`Integrator::may_use_compensated_environment`]): its estimate would be biased.
    pub fn new(scene: &'a Scene, integrator: &'a Integrator, seed: u64) -> Self {
        assert!(
            !scene.environment_compensated() || integrator.may_use_compensated_environment(scene),
            "RenderJob::new: the scene's environment maps sample by MIS-compensated tables, which \
             only an integrator weighing every emitter sample by MIS may use \
             (Scene::set_environment_compensation(false) first)"
        );
        RenderJob {
            scene,
            integrator,
            seed,
        }
    }

    /// The image's width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.scene.camera.width, self.scene.camera.height)
    }

    /// Whether the integrator shares light among the pixels of a group ([`GROUP`] pixels,
    /// 4x2): then a pixel's values depend on its group's paths, and render loops go group by
    /// group ([`RenderJob::group_of`], [`RenderJob::group`]).
    #[inline]
    pub fn reuses(&self) -> bool {
        reuses(self.integrator)
    }

    /// Radiance of sample `index` of pixel `(x, y)`.
    #[inline]
    pub fn sample(&self, x: u32, y: u32, index: u64) -> Color {
        self.sample_probed(x, y, index, &mut NoProbe)
    }

    /// [`RenderJob::sample`], telling `probe` about the work done: the same value for any
    /// probe.
    #[inline]
    pub fn sample_probed<P: Probe>(&self, x: u32, y: u32, index: u64, probe: &mut P) -> Color {
        let mut c = Color::ZERO;
        let mut cache = PixelCache::default();
        self.pixel(x, y, index..index + 1, &mut cache, probe, |v, _| c = v);
        c
    }

    /// Adds samples `samples` of pixel `(x, y)` to `acc`, in index order (the pixel's own
    /// samples, whatever the reconstruction: see [`RenderJob::pixel`]).
    pub fn accumulate(&self, x: u32, y: u32, samples: Range<u64>, acc: &mut PixelAccum) {
        let mut cache = PixelCache::default();
        self.pixel(x, y, samples, &mut cache, &mut NoProbe, |c, _| acc.add(c));
    }

    /// Samples `samples` of pixel `(x, y)` in index order, each value passed to `add` with where
    /// the sample lies: the values of [`RenderJob::sample_probed`] for those indices, bit for
    /// bit, for any `cache` (fresh or used by other pixels, seeds or sample counts). The offset
    /// from the pixel's centre is what splatting weighs the sample by (with the scene's
    /// [`Footprint`](crate::splat::Footprint)); with filter importance sampling it is the
    /// sampled offset, already accounted for. The cache, kept from pixel to pixel by the caller,
    /// spares the zsobol sampler's per-pixel work ([`ZSobolPixel`]).
    #[inline]
    pub fn pixel<P: Probe>(
        &self,
        x: u32,
        y: u32,
        samples: Range<u64>,
        cache: &mut PixelCache,
        probe: &mut P,
        mut add: impl FnMut(Color, Vec2),
    ) {
        if self.reuses() {
            // The pixel's values depend on its group's paths: trace the group, keep this pixel's.
            let (pixels, n) = self.group_of(x, y);
            let me = pixels[..n].iter().position(|&p| p == (x, y)).unwrap_or(0);
            let mut caches = GroupCache::default();
            let all: [Range<u64>; GROUP] = core::array::from_fn(|_| samples.clone());
            self.group(&pixels[..n], &all[..n], &mut caches, probe, |k, _, c, o| {
                if k == me {
                    add(c, o)
                }
            });
            return;
        }
        self.pixel_alone(x, y, samples, cache, probe, |c, o, _| add(c, o));
    }

    /// [`RenderJob::pixel`] for an integrator that does not reuse, each value passed to `add`
    /// with its offset and its [`CameraSample`] (what a caller gathering other variables of the
    /// same camera rays needs: see `AovIntegrator::value`).
    ///
    /// # Panics
    /// If the integrator reuses paths ([`RenderJob::reuses`]): a sample's value then depends on
    /// its group, not only on its camera ray.
    #[inline]
    pub fn pixel_alone<P: Probe>(
        &self,
        x: u32,
        y: u32,
        samples: Range<u64>,
        cache: &mut PixelCache,
        probe: &mut P,
        mut add: impl FnMut(Color, Vec2, &CameraSample),
    ) {
        assert!(!self.reuses(), "pixel_alone: the integrator reuses paths");
        match self.scene.sampler {
            SamplerKind::Independent => {
                // The camera rays of a few samples first, then their paths: the rays' chains of
                // divisions and square roots, each waiting on the one before, overlap when they
                // sit together (each sample keeps its own sampler, so no value moves).
                let finisher = CameraBatch::of::<P>(self.scene, self.integrator);
                let mut run = IndependentSampler::pixel_run(self.seed, x, y, samples);
                loop {
                    let batch: [Option<CameraDraw<IndependentSampler>>; CAMERA_BATCH] =
                        core::array::from_fn(|_| run.next().map(|s| self.camera_draw(x, y, s)));
                    if batch[0].is_none() {
                        break;
                    }
                    let draws = batch.into_iter().flatten();
                    self.finish_draws(finisher.as_ref(), draws, probe, &mut add);
                }
            }
            SamplerKind::ZSobol { log2_spp } => {
                if samples.is_empty() {
                    return;
                }
                let pixel = cache.zsobol_for(self.seed, x, y, log2_spp, samples.clone());
                let Some(esc) = Escapes::of::<P>(self.scene, self.integrator) else {
                    for index in samples {
                        let (c, o, cam) = self.trace(x, y, pixel.sampler(index), probe);
                        add(c, o, &cam);
                    }
                    return;
                };
                let mut pending = Pending::default();
                for index in samples {
                    let draw = self.camera_draw(x, y, pixel.sampler(index));
                    esc.push(self.scene, &mut pending, draw, probe);
                    if pending.is_full() {
                        esc.flush(&mut pending, &mut add);
                    }
                }
                esc.flush(&mut pending, &mut add);
            }
        }
    }

    /// The samples whose camera parts are `draws` (at most [`CAMERA_BATCH`]): each value,
    /// offset and camera sample passed to `add` in order, through `batch` when it applies,
    /// else by [`RenderJob::finish`] one by one (the same bits either way).
    #[inline(always)]
    pub(crate) fn finish_draws<S: Sampler, P: Probe>(
        &self,
        batch: Option<&CameraBatch>,
        draws: impl Iterator<Item = CameraDraw<S>>,
        probe: &mut P,
        add: &mut impl FnMut(Color, Vec2, &CameraSample),
    ) {
        match batch {
            Some(batch) => batch.finish(self.scene, draws, probe, add),
            None => {
                for draw in draws {
                    let (c, o, cam) = self.finish(draw, probe);
                    add(c, o, &cam);
                }
            }
        }
    }

    /// The pixels of the group that holds pixel `(x, y)`: the `GROUP_W x GROUP_H` block at
    /// multiples of those, clipped to the image, in row order; the second value is how many
    /// there are.
    pub fn group_of(&self, x: u32, y: u32) -> ([(u32, u32); GROUP], usize) {
        let (w, h) = self.size();
        let (x0, y0) = (x - x % GROUP_W, y - y % GROUP_H);
        let mut pixels = [(x0, y0); GROUP];
        let mut n = 0;
        for py in (y0..y0 + GROUP_H).filter(|&py| py < h) {
            for px in (x0..x0 + GROUP_W).filter(|&px| px < w) {
                pixels[n] = (px, py);
                n += 1;
            }
        }
        (pixels, n)
    }

    /// Every pixel of a group (`pixels`, as [`RenderJob::group_of`] gives them) takes its
    /// samples `samples[k]`, sample index by sample index over their union: `add(k, index,
    /// value, offset)` gets pixel `k`'s value of each of its samples in index order, and where
    /// it lies (as [`RenderJob::pixel`] gives it). At each index the
    /// pixels that take it share their light (with an integrator that [`reuses`]); so each value
    /// is a pure function of the job, the group, the pixel, the sample index and which of the
    /// group's pixels take that index (all of them when the ranges are equal, as in every render
    /// but an adaptive pass). With an integrator that does not reuse, it is
    /// [`RenderJob::sample_probed`]'s.
    pub fn group<P: Probe>(
        &self,
        pixels: &[(u32, u32)],
        samples: &[Range<u64>],
        caches: &mut GroupCache,
        probe: &mut P,
        mut add: impl FnMut(usize, u64, Color, Vec2),
    ) {
        let n = pixels.len().min(GROUP).min(samples.len());
        let Integrator::Path(path) = self.integrator else {
            for (k, &(x, y)) in pixels[..n].iter().enumerate() {
                let cache = &mut caches.pixels[k];
                let mut index = samples[k].start;
                self.pixel_alone(x, y, samples[k].clone(), cache, probe, |c, o, _| {
                    add(k, index, c, o);
                    index += 1;
                });
            }
            return;
        };
        let live = samples[..n].iter().filter(|r| !r.is_empty());
        let lo = live.clone().map(|r| r.start).min();
        let hi = live.map(|r| r.end).max();
        let (Some(lo), Some(hi)) = (lo, hi) else {
            return;
        };
        let group = &pixels[..n];
        match self.scene.sampler {
            SamplerKind::Independent => {
                for index in lo..hi {
                    let mut samplers = core::array::from_fn::<_, GROUP, _>(|k| {
                        let (x, y) = pixels[k.min(n - 1)];
                        IndependentSampler::new(self.seed, x, y, index)
                    });
                    self.group_sample(path, group, samples, index, &mut samplers, probe, &mut add);
                }
            }
            SamplerKind::ZSobol { log2_spp } => {
                for k in 0..GROUP {
                    let (x, y) = pixels[k.min(n - 1)];
                    caches.pixels[k].zsobol_for(self.seed, x, y, log2_spp, lo..hi);
                }
                for index in lo..hi {
                    let mut samplers = caches.pixels.each_mut().map(|p| match &mut p.zsobol {
                        Some(z) => z.sampler(index),
                        None => unreachable!("every pixel cache was set above"),
                    });
                    self.group_sample(path, group, samples, index, &mut samplers, probe, &mut add);
                }
            }
        }
    }

    /// Sample `index` of each pixel of a group (`pixels`) whose range in `samples` holds it:
    /// camera rays drawn from those pixels' samplers (`samplers[k]` is pixel `k`'s; the others,
    /// and any past the group's size, are not touched), then the group estimator; each value
    /// goes to `add(k, index, value, offset)`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn group_sample<S: Sampler, P: Probe>(
        &self,
        path: &PathIntegrator,
        pixels: &[(u32, u32)],
        samples: &[Range<u64>],
        index: u64,
        samplers: &mut [S; GROUP],
        probe: &mut P,
        add: &mut impl FnMut(usize, u64, Color, Vec2),
    ) {
        let n = pixels.len();
        let mut rays = [None; GROUP];
        let mut weights = [None; GROUP];
        let mut offsets = [Vec2::ZERO; GROUP];
        for (k, s) in samplers[..n].iter_mut().enumerate() {
            if !samples[k].contains(&index) {
                continue;
            }
            let (x, y) = pixels[k];
            let (offset, weight) = self.camera_offset(s.next_2d());
            weights[k] = weight;
            offsets[k] = offset;
            let pos = Vec2::new(x as f32 + 0.5 + offset.x, y as f32 + 0.5 + offset.y);
            let ray = self.scene.camera.sample_ray(pos, s);
            probe.camera(pos, &ray);
            rays[k] = Some(ray);
        }
        let mut out = [Color::ZERO; GROUP];
        path.li_group(
            self.scene,
            &rays[..n],
            &mut samplers[..n],
            probe,
            &mut out[..n],
        );
        for k in (0..n).filter(|&k| rays[k].is_some()) {
            add(
                k,
                index,
                weights[k].map_or(out[k], |w| out[k] * w),
                offsets[k],
            );
        }
    }

    /// A camera sample's offset from its pixel's centre, from the sampler's first two
    /// dimensions `u`, and the weight its radiance takes: uniform in the pixel when the scene
    /// splats (the film weighs the sample), else drawn from the filter
    /// ([`Filter::sample_weighted`](crate::camera::Filter::sample_weighted)).
    #[inline]
    fn camera_offset(&self, u: Vec2) -> (Vec2, Option<f32>) {
        if self.scene.splat.is_some() {
            (u - Vec2::splat(0.5), None)
        } else {
            self.scene.filter.sample_weighted(u)
        }
    }

    /// One camera sample of pixel `(x, y)` drawn from `sampler`, and its offset from the pixel's
    /// centre.
    #[inline]
    fn trace<S: Sampler, P: Probe>(
        &self,
        x: u32,
        y: u32,
        sampler: S,
        probe: &mut P,
    ) -> (Color, Vec2, CameraSample) {
        let draw = self.camera_draw(x, y, sampler);
        self.finish(draw, probe)
    }

    /// The camera part of a sample of pixel `(x, y)`: its film position and camera ray, drawn
    /// from the first dimensions of `sampler`, which the path goes on drawing from.
    #[inline(always)]
    pub(crate) fn camera_draw<S: Sampler>(&self, x: u32, y: u32, mut sampler: S) -> CameraDraw<S> {
        let (offset, weight) = self.camera_offset(sampler.next_2d());
        let pos = Vec2::new(x as f32 + 0.5 + offset.x, y as f32 + 0.5 + offset.y);
        let ray = self.scene.camera.sample_ray(pos, &mut sampler);
        CameraDraw {
            sampler,
            pos,
            offset,
            cam: CameraSample { ray, weight },
        }
    }

    /// The sample whose camera part is `draw`: its value (weighted for filters with negative
    /// lobes), its offset from the pixel's centre and its camera sample.
    #[inline(always)]
    pub(crate) fn finish<S: Sampler, P: Probe>(
        &self,
        draw: CameraDraw<S>,
        probe: &mut P,
    ) -> (Color, Vec2, CameraSample) {
        let CameraDraw {
            mut sampler,
            pos,
            offset,
            cam,
        } = draw;
        probe.camera(pos, &cam.ray);
        let l = self
            .integrator
            .li_probed(self.scene, cam.ray, &mut sampler, probe);
        // Filters with negative lobes weight their samples; the others give no weight.
        (cam.weigh(l), offset, cam)
    }
}

/// Whether `integrator` shares light among the pixels of a group (see [`RenderJob::reuses`]).
#[inline]
pub fn reuses(integrator: &Integrator) -> bool {
    matches!(integrator, Integrator::Path(p) if p.reuses())
}

/// What the pixels one worker renders one after another share: the zsobol sampler's table of
/// pixel parts (reused, not rebuilt, for each pixel) and its dimensions' hashes (the same for
/// every pixel). It holds no result: any cache gives the same values.
#[derive(Clone, Debug, Default)]
pub struct PixelCache {
    zsobol: Option<ZSobolPixel>,
}

impl PixelCache {
    /// The zsobol cache, moved to pixel `(x, y)` (made on first use) and told its run.
    #[inline]
    fn zsobol_for(
        &mut self,
        seed: u64,
        x: u32,
        y: u32,
        log2_spp: u32,
        run: Range<u64>,
    ) -> &mut ZSobolPixel {
        let pixel = match &mut self.zsobol {
            Some(p) => {
                p.move_to(seed, x, y, log2_spp);
                p
            }
            none => none.insert(ZSobolPixel::new(seed, x, y, log2_spp)),
        };
        pixel.set_run(run);
        pixel
    }
}

/// One sampler cache per pixel of a group.
#[derive(Clone, Debug, Default)]
pub struct GroupCache {
    pixels: [PixelCache; GROUP],
}

//! Error against time with every wave's image rendered afresh (`tessera bench --fresh`).
//!
//! [`super::run_waves`] continues one sample sequence: after wave `k` the image holds the first
//! `2^k` samples of a sampler set up for `--max-spp` samples, and a row's time is the sum of the
//! waves so far. A user who renders 8 spp sets the sampler up for 8 samples instead (the scene's
//! `sample_count`, e.g. `tessera render scenes/cbox.xml -D spp=8`), and zsobol's first 8 of a
//! block of 2^20 are not as well spread as a whole block of 8 (on cbox, reuse, 8 spp: 12% more
//! relMSE). Mitsuba's bench script renders each wave from scratch. Here wave `k` does the same:
//! a new framebuffer, the sampler set up for `2^k` samples ([`SamplerKind::for_spp`]), and the
//! row's time is that render's time alone. The image is bit for bit a render with
//! `sample_count` `2^k` and the same seed. With adaptive sampling it is the continuing waves'
//! schedule run from scratch up to `2^k`, with the sampler set up as `render --adaptive` sets
//! it up for `sample_count` `2^k` (zsobol blocks [`ZSOBOL_BLOCK_FACTOR`] times the count, so the
//! noisiest pixels, which take several times the mean, stay in one stratified block): bit for
//! bit that command's image.
//!
//! A curve costs about twice the continuing one (each wave repeats the work of all before it).
//! Its rows name the sampler with `+fresh` appended (`zsobol+fresh`, `zsobol+adaptive+fresh`).
use super::{errors, run_waves, Row, WaveLimits};
use std::time::Instant;
use tessera::image_io::RgbImage;
use tessera::render::{render, RenderOptions};
use tessera_core::adaptive::{AdaptiveParams, ZSOBOL_BLOCK_FACTOR};
use tessera_core::integrator::Integrator;
use tessera_core::render::RenderJob;
use tessera_core::sampling::SamplerKind;
use tessera_core::scene::Scene;

/// Renders `integrator` afresh at 1, 2, 4, ... spp until a limit is reached (no render starts
/// whose predicted time, twice the last one's, passes `limits.max_seconds`; the first always
/// runs), calling `on_wave` with each row; returns the rows. Every render is seeded with `seed`. `scene.sampler` is set up for each
/// wave's count in turn (as `render --adaptive` sets it up, with `adaptive`) and restored before
/// returning.
#[allow(clippy::too_many_arguments)]
pub fn run_fresh(
    scene: &mut Scene,
    integrator: &Integrator,
    seed: u64,
    label: &str,
    opts: &RenderOptions,
    reference: &RgbImage,
    limits: WaveLimits,
    adaptive: Option<&AdaptiveParams>,
    on_wave: &mut dyn FnMut(&Row),
) -> Vec<Row> {
    let base = scene.sampler;
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut rows: Vec<Row> = Vec::new();
    let mut spp = 1u64;
    while spp <= limits.max_spp.max(1) {
        if let Some(last) = rows.last() {
            if 2.0 * last.seconds > limits.max_seconds {
                break;
            }
        }
        let block = match adaptive {
            Some(_) => spp.saturating_mul(ZSOBOL_BLOCK_FACTOR),
            None => spp,
        };
        scene.sampler = base.for_spp(block);
        let job = RenderJob::new(scene, integrator, seed);
        let (seconds, rgb) = match adaptive {
            Some(a) => {
                let to_spp = WaveLimits {
                    max_seconds: f64::INFINITY,
                    max_spp: spp,
                };
                let (waves, fb) =
                    run_waves(&job, label, opts, reference, to_spp, Some(a), &mut |_| {});
                let seconds = waves.last().map_or(0.0, |r| r.seconds);
                (seconds, fb.rgb())
            }
            None => {
                let start = Instant::now();
                let fb = render(&job, 0..spp, opts, &mut |_, _| {});
                (start.elapsed().as_secs_f64(), fb.rgb())
            }
        };
        let row = Row {
            integrator: label.to_string(),
            sampler: fresh_name(base, adaptive.is_some()),
            spp,
            threads: opts.threads,
            seconds,
            samples_per_second: (w as f64 * h as f64 * spp as f64) / seconds.max(1e-9),
            errors: errors(&rgb, &reference.data),
        };
        on_wave(&row);
        rows.push(row);
        match spp.checked_mul(2) {
            Some(next) => spp = next,
            None => break,
        }
    }
    scene.sampler = base;
    rows
}

/// The sampler column of a fresh curve's rows.
pub fn fresh_name(sampler: SamplerKind, adaptive: bool) -> String {
    let mode = if adaptive { "+adaptive" } else { "" };
    format!("{}{mode}+fresh", sampler.name())
}

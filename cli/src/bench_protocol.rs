//! `tessera bench`'s default measurement, the protocol the README's efficiency table follows:
//! what a user's render costs and how far its image is from the reference, at a sample count
//! large enough that fixed costs do not dominate.
//!
//! Each run is what `tessera render` does for one image: the scene file loaded (parsed, meshes
//! and textures read, the acceleration structure built), the sampler set up for the run's
//! sample count, the image rendered; its seconds are all of that. Runs start at `--min-spp`
//! (64) and the sample count grows (by the power of two that should reach the time, at least
//! doubling) until a run takes `--min-seconds` (5 s) or reaches `--max-spp`; that last count is
//! rendered once more and the faster of the two is kept (the first run at a count pays for
//! caches the second finds warm, and on a shared machine the faster of two identical runs is
//! the better estimate). Every run is a row of the report; the last row's relMSE times its
//! seconds is the curve's efficiency, which for an unbiased renderer does not depend on the
//! sample count (lower is better). `scripts/protocol_bench.py` measures Mitsuba 3 the same way
//! and prints the ratio.
use std::path::Path;
use std::time::Instant;
use tessera::image_io::RgbImage;
use tessera::render::{render, RenderOptions};
use tessera_core::render::RenderJob;
use tessera_lab::bench::{errors, Row};
use tessera_scene::load_scene;

/// Where a protocol curve starts and stops.
#[derive(Clone, Copy, Debug)]
pub struct ProtocolLimits {
    /// The first run's samples per pixel.
    pub min_spp: u64,
    /// A run at least this long ends the curve.
    pub min_seconds: f64,
    /// So does this many samples per pixel.
    pub max_spp: u64,
}

/// What one curve measures: the scene and its defines, the integrator and sampler to set.
pub struct ProtocolCurve<'a> {
    /// The scene file.
    pub scene: &'a Path,
    /// `-D` overrides.
    pub defines: &'a [(String, String)],
    /// Integrator name (as `--integrator` takes it).
    pub integrator: &'a str,
    /// Sampler name, or the scene's own.
    pub sampler: Option<&'a str>,
    /// Longest path override.
    pub max_depth: Option<i64>,
    /// Seed, or the scene's own.
    pub seed: Option<u64>,
}

/// One run: load, set up, render `spp`; the row (seconds are the whole run's).
fn run_once(
    c: &ProtocolCurve,
    spp: u64,
    opts: &RenderOptions,
    reference: &RgbImage,
) -> Result<Row, String> {
    let start = Instant::now();
    let mut loaded = load_scene(c.scene, c.defines).map_err(|e| e.to_string())?;
    loaded.set_integrator(Some(c.integrator), c.max_depth)?;
    // Set up for the count rendered, as `tessera render --spp` sets it up.
    loaded.set_sampler_for(c.sampler, spp)?;
    let seed = c.seed.unwrap_or(loaded.seed);
    let job = RenderJob::new(&loaded.scene, &loaded.integrator, seed);
    let rgb = render(&job, 0..spp, opts, &mut |_, _| {}).rgb();
    let seconds = start.elapsed().as_secs_f64();
    let (w, h) = (loaded.scene.camera.width, loaded.scene.camera.height);
    Ok(Row {
        integrator: c.integrator.to_string(),
        sampler: loaded.scene.sampler.name().to_string(),
        spp,
        threads: opts.threads,
        seconds,
        samples_per_second: (w as f64 * h as f64 * spp as f64) / seconds.max(1e-9),
        errors: errors(&rgb, &reference.data),
    })
}

/// The next sample count after a run of `spp` that took `seconds`: the power-of-two multiple
/// expected to take `min_seconds`, at least double, at most `max_spp`.
fn next_spp(spp: u64, seconds: f64, limits: &ProtocolLimits) -> u64 {
    let want = (limits.min_seconds / seconds.max(1e-3))
        .log2()
        .ceil()
        .max(1.0);
    let factor = 1u64 << (want.min(20.0) as u32);
    spp.saturating_mul(factor).min(limits.max_spp)
}

/// Measures one curve; calls `on_run` with each row (the repeat of the last count included,
/// before the faster is kept). Returns the rows, the kept final run last.
pub fn run_protocol(
    c: &ProtocolCurve,
    opts: &RenderOptions,
    reference: &RgbImage,
    limits: &ProtocolLimits,
    on_run: &mut dyn FnMut(&Row),
) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    let mut spp = limits.min_spp.min(limits.max_spp).max(1);
    loop {
        let row = run_once(c, spp, opts, reference)?;
        on_run(&row);
        if row.seconds >= limits.min_seconds || spp >= limits.max_spp {
            let again = run_once(c, spp, opts, reference)?;
            on_run(&again);
            rows.push(if again.seconds < row.seconds {
                again
            } else {
                row
            });
            return Ok(rows);
        }
        spp = next_spp(spp, row.seconds, limits);
        rows.push(row);
    }
}

/// The curve's efficiency line: its last run's sample count, seconds, relMSE and their product.
pub fn efficiency_line(rows: &[Row]) -> Option<String> {
    let r = rows.last()?;
    Some(format!(
        "{} ({}, {} threads): {} spp in {:.2} s (load included), relMSE {:.4e}, efficiency \
         (relMSE x seconds) {:.4e}",
        r.integrator,
        r.sampler,
        r.threads,
        r.spp,
        r.seconds,
        r.errors.relmse,
        r.errors.relmse * r.seconds
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_next_count_aims_at_the_time_and_at_least_doubles() {
        let l = ProtocolLimits {
            min_spp: 64,
            min_seconds: 5.0,
            max_spp: 1 << 20,
        };
        assert_eq!(next_spp(64, 4.0, &l), 128);
        assert_eq!(next_spp(64, 1.0, &l), 512);
        assert_eq!(next_spp(64, 0.3, &l), 64 * 32);
        assert_eq!(next_spp(1 << 19, 0.001, &l), 1 << 20);
    }
}

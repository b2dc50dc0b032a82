//! Error against time: renders in waves of doubling sample counts, measures each wave's image
//! against a converged reference, and keeps the rows of a CSV report.
//!
//! Wave `k` (k = 0, 1, 2, ...) adds the sample indices `[2^k / 2, 2^k)` (wave 0: `[0, 1)`) to
//! one framebuffer, so after wave `k` the image is bit for bit a plain `2^k` spp render (with the
//! scene's sampler as it is set up: `tessera bench` sets zsobol up for `--max-spp` samples, so
//! its waves are the first `2^k` samples of every pixel's block of that size). A row's
//! `seconds` is the wall time spent rendering that image (the sum of its waves), never the time
//! spent measuring it. `fresh::run_fresh` (`tessera bench --fresh`) instead renders each
//! wave's image from scratch, the sampler set up for that wave's count, as a user's render and
//! Mitsuba's bench script do.
//!
//! CSV columns ([`CSV_HEADER`]): `integrator, sampler, spp, threads, seconds,
//! samples_per_second, rmse, relmse, mae`; `samples_per_second` is pixels x spp / seconds.
//! `scripts/mitsuba_bench.py` appends rows of the same form (integrator `mitsuba:NAME`).
pub mod fresh;
pub mod mean;
pub mod plot;
pub mod ratio;
pub mod repeat;

use std::path::Path;
use std::time::Instant;
use tessera::image_io::{write_atomic, RgbImage};
use tessera::render::{render_span, Framebuffer, RenderOptions, Span};
use tessera_core::adaptive::{pass_targets, AdaptiveParams};
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;

/// The header line of a report.
pub const CSV_HEADER: &str =
    "integrator,sampler,spp,threads,seconds,samples_per_second,rmse,relmse,mae";

/// One measured image.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Curve label: a Tessera integrator name, or e.g. `mitsuba:path`.
    pub integrator: String,
    /// Sampler name (`independent`, `zsobol`).
    pub sampler: String,
    /// Samples per pixel of the image.
    pub spp: u64,
    /// Worker threads.
    pub threads: usize,
    /// Wall seconds spent rendering the image.
    pub seconds: f64,
    /// Pixel samples per second (pixels x spp / seconds).
    pub samples_per_second: f64,
    /// Errors against the reference.
    pub errors: Errors,
}

/// Errors of an image against a reference, over every pixel and channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Errors {
    /// Root mean squared error.
    pub rmse: f64,
    /// Relative MSE: mean of (a - b)^2 / (b^2 + 0.01).
    pub relmse: f64,
    /// Mean absolute error.
    pub mae: f64,
}

/// Errors of `img` against `reference` (same length; compared up to the shorter one).
pub fn errors(img: &[[f32; 3]], reference: &[[f32; 3]]) -> Errors {
    let (mut se, mut rel, mut ae, mut n) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    for (a, b) in img.iter().zip(reference) {
        for c in 0..3 {
            let (a, b) = (a[c] as f64, b[c] as f64);
            let d = a - b;
            se += d * d;
            rel += d * d / (b * b + 0.01);
            ae += d.abs();
            n += 1;
        }
    }
    let n = n.max(1) as f64;
    Errors {
        rmse: (se / n).sqrt(),
        relmse: rel / n,
        mae: ae / n,
    }
}

/// When to stop a curve.
#[derive(Clone, Copy, Debug)]
pub struct WaveLimits {
    /// No wave starts whose predicted end (it costs about as much as everything before it)
    /// passes this many seconds; the first wave always runs.
    pub max_seconds: f64,
    /// No wave goes beyond this many samples per pixel.
    pub max_spp: u64,
}

/// Renders `integrator` in waves 1, 2, 4, ... spp into one framebuffer until a limit is reached,
/// calling `on_wave` with each row; returns the rows and the final framebuffer.
///
/// With `adaptive`, the waves after the warm-up (`adaptive.warmup` samples in every pixel) share
/// the same budgets (pixels x spp) out by [`pass_targets`]: a row's `spp` is then the mean over
/// pixels, and its sampler is named `SAMPLER+adaptive`. The time to plan a pass counts in the
/// wave's seconds.
#[allow(clippy::too_many_arguments)]
pub fn run_waves(
    job: &RenderJob,
    label: &str,
    opts: &RenderOptions,
    reference: &RgbImage,
    limits: WaveLimits,
    adaptive: Option<&AdaptiveParams>,
    on_wave: &mut dyn FnMut(&Row),
) -> (Vec<Row>, Framebuffer) {
    let (w, h) = job.size();
    let mut fb = Framebuffer::for_job(job);
    let mut rows = Vec::new();
    let (mut done, mut seconds) = (0u64, 0.0f64);
    loop {
        let next = if done == 0 { 1 } else { done * 2 };
        if next > limits.max_spp.max(1) || (done > 0 && 2.0 * seconds > limits.max_seconds) {
            break;
        }
        let start = Instant::now();
        match adaptive {
            Some(a) if done >= a.warmup.max(1) => {
                let pixels = w as u64 * h as u64;
                let a = &a.for_integrator(job.integrator);
                let targets = pass_targets(&fb.pixels, w, h, pixels * (next - done), a);
                let span = Span::Targets(&targets);
                render_span::<NoProbe>(job, opts, &mut fb, span, None, &mut |_, _| {});
            }
            Some(_) => {
                // The warm-up, with per-pixel targets as `render --adaptive` has: its rays are
                // counted, and the passes price samples by them.
                let targets = vec![next; fb.pixels.len()];
                let span = Span::Targets(&targets);
                render_span::<NoProbe>(job, opts, &mut fb, span, None, &mut |_, _| {});
            }
            None => {
                let span = Span::Fixed(done..next);
                render_span::<NoProbe>(job, opts, &mut fb, span, None, &mut |_, _| {});
            }
        }
        seconds += start.elapsed().as_secs_f64();
        done = next;
        let sampler = match adaptive {
            Some(_) => format!("{}+adaptive", job.scene.sampler.name()),
            None => job.scene.sampler.name().into(),
        };
        let row = Row {
            integrator: label.to_string(),
            sampler,
            spp: done,
            threads: opts.threads,
            seconds,
            samples_per_second: (w as f64 * h as f64 * done as f64) / seconds.max(1e-9),
            errors: errors(&fb.rgb(), &reference.data),
        };
        on_wave(&row);
        rows.push(row);
    }
    (rows, fb)
}

impl Row {
    /// The row as a CSV line (no newline); floats in shortest round-trip form.
    pub fn to_csv(&self) -> String {
        format!(
            "{},{},{},{},{},{},{},{},{}",
            self.integrator,
            self.sampler,
            self.spp,
            self.threads,
            self.seconds,
            self.samples_per_second,
            self.errors.rmse,
            self.errors.relmse,
            self.errors.mae
        )
    }

    /// Parses a CSV line written by [`Row::to_csv`] (or by `scripts/mitsuba_bench.py`).
    pub(crate) fn from_csv(line: &str) -> Result<Row, String> {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 9 {
            return Err(format!("expected 9 fields, found {}", f.len()));
        }
        let num = |i: usize| -> Result<f64, String> {
            f[i].parse::<f64>()
                .map_err(|_| format!("field {} is not a number: \"{}\"", i + 1, f[i]))
        };
        let int = |i: usize| -> Result<u64, String> {
            f[i].parse::<u64>()
                .map_err(|_| format!("field {} is not a count: \"{}\"", i + 1, f[i]))
        };
        Ok(Row {
            integrator: f[0].to_string(),
            sampler: f[1].to_string(),
            spp: int(2)?,
            threads: int(3)? as usize,
            seconds: num(4)?,
            samples_per_second: num(5)?,
            errors: Errors {
                rmse: num(6)?,
                relmse: num(7)?,
                mae: num(8)?,
            },
        })
    }
}

/// Writes a report (header and rows) atomically.
pub fn write_csv(path: &Path, rows: &[Row]) -> Result<(), String> {
    let mut text = String::from(CSV_HEADER);
    text.push('\n');
    for r in rows {
        text.push_str(&r.to_csv());
        text.push('\n');
    }
    write_atomic(path, |tmp| {
        std::fs::write(tmp, text).map_err(|e| e.to_string())
    })
    .map_err(|e| format!("{}: cannot write report: {e}", path.display()))
}

/// Reads a report; errors name the file and line.
pub fn read_csv(path: &Path) -> Result<Vec<Row>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read report: {e}", path.display()))?;
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim() == CSV_HEADER => {}
        _ => {
            return Err(format!(
                "{}:1: not a bench report (the first line must be \"{CSV_HEADER}\")",
                path.display()
            ))
        }
    }
    lines
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| Row::from_csv(l).map_err(|e| format!("{}:{}: {e}", path.display(), i + 1)))
        .collect()
}

impl Row {
    /// The curve this row belongs to: the integrator label, followed by the sampler in
    /// parentheses unless it is `independent`.
    pub fn curve_label(&self) -> String {
        if self.sampler == "independent" {
            self.integrator.clone()
        } else {
            format!("{} ({})", self.integrator, self.sampler)
        }
    }
}

/// The rows grouped into curves by [`Row::curve_label`], in order of first appearance.
pub fn curves(rows: &[Row]) -> Vec<(String, Vec<Row>)> {
    let mut out: Vec<(String, Vec<Row>)> = Vec::new();
    for r in rows {
        let label = r.curve_label();
        match out.iter_mut().find(|(name, _)| *name == label) {
            Some((_, v)) => v.push(r.clone()),
            None => out.push((label, vec![r.clone()])),
        }
    }
    out
}

/// When a curve first reaches a relMSE.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimeToTarget {
    /// Reached between two waves: seconds interpolated linearly in log(seconds) against
    /// log(relMSE) between the last wave above the target and the first at or below it.
    Interpolated(f64),
    /// Already reached by the first image (at most this many seconds).
    AtMost(f64),
    /// Not reached; the lowest relMSE seen and when.
    NotReached {
        /// Lowest relMSE of the curve.
        best: f64,
        /// Its seconds.
        seconds: f64,
    },
}

/// When the rows of one curve (in wave order) first reach `target` relMSE.
pub fn time_to_target(curve: &[Row], target: f64) -> TimeToTarget {
    let mut prev: Option<&Row> = None;
    for r in curve {
        if r.errors.relmse <= target {
            return match prev {
                None => TimeToTarget::AtMost(r.seconds),
                Some(p) => {
                    let (e0, e1) = (p.errors.relmse.ln(), r.errors.relmse.ln());
                    let (t0, t1) = (p.seconds.max(1e-12).ln(), r.seconds.max(1e-12).ln());
                    let f = if e1 < e0 {
                        (target.ln() - e0) / (e1 - e0)
                    } else {
                        1.0
                    };
                    TimeToTarget::Interpolated((t0 + f.clamp(0.0, 1.0) * (t1 - t0)).exp())
                }
            };
        }
        prev = Some(r);
    }
    let best = curve
        .iter()
        .min_by(|a, b| a.errors.relmse.total_cmp(&b.errors.relmse));
    TimeToTarget::NotReached {
        best: best.map_or(f64::NAN, |r| r.errors.relmse),
        seconds: best.map_or(f64::NAN, |r| r.seconds),
    }
}

impl std::fmt::Display for TimeToTarget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            TimeToTarget::Interpolated(s) => write!(f, "{s:.3} s"),
            TimeToTarget::AtMost(s) => write!(f, "<= {s:.3} s (first wave)"),
            TimeToTarget::NotReached { best, seconds } => {
                write!(f, "not reached (best relMSE {best:.3e} at {seconds:.3} s)")
            }
        }
    }
}

/// A row of a curve named `x` with only its time and relMSE set (for unit tests of what reads
/// curves).
#[cfg(test)]
pub(crate) fn test_row(seconds: f64, relmse: f64) -> Row {
    Row {
        integrator: "x".into(),
        sampler: "independent".into(),
        spp: 1,
        threads: 1,
        seconds,
        samples_per_second: 1.0,
        errors: Errors {
            rmse: 0.0,
            relmse,
            mae: 0.0,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::test_row as row;
    use super::*;

    #[test]
    fn errors_of_a_known_pair() {
        // Two pixels: differences (1, 0, 0) and (0, 0, -0.5) against references 0 and 1.
        let img = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.5]];
        let reference = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]];
        let e = errors(&img, &reference);
        let rel = (1.0 / 0.01 + 0.25 / 1.01) / 6.0;
        assert!((e.relmse - rel).abs() < 1e-12, "{e:?}");
        assert!((e.rmse - (1.25f64 / 6.0).sqrt()).abs() < 1e-12, "{e:?}");
        assert!((e.mae - 1.5 / 6.0).abs() < 1e-12, "{e:?}");
        assert_eq!(errors(&reference, &reference).relmse, 0.0);
    }

    #[test]
    fn time_to_target_interpolates_in_log_log() {
        // relMSE falls as 1/t: 0.04 at 1 s, 0.01 at 4 s -> 0.02 is reached at 2 s.
        let c = [row(0.5, 0.08), row(1.0, 0.04), row(4.0, 0.01)];
        match time_to_target(&c, 0.02) {
            TimeToTarget::Interpolated(s) => assert!((s - 2.0).abs() < 1e-9, "{s}"),
            t => panic!("{t:?}"),
        }
        assert_eq!(time_to_target(&c, 0.1), TimeToTarget::AtMost(0.5));
        assert_eq!(
            time_to_target(&c, 0.001),
            TimeToTarget::NotReached {
                best: 0.01,
                seconds: 4.0
            }
        );
    }

    #[test]
    fn csv_round_trip() {
        let r = Row {
            integrator: "mitsuba:path".into(),
            sampler: "independent".into(),
            spp: 64,
            threads: 2,
            seconds: 1.25,
            samples_per_second: 3.5e6,
            errors: Errors {
                rmse: 0.1,
                relmse: 1.5e-3,
                mae: 0.03125,
            },
        };
        assert_eq!(Row::from_csv(&r.to_csv()), Ok(r));
        assert!(Row::from_csv("a,b,c").is_err());
    }
}

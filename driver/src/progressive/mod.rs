//! Progressive rendering: passes of whole-image samples until a target sample count, a time
//! budget or a stop request, with the current average written out every so often.
//!
//! Every pass brings each pixel from its own sample count up to the pass's end
//! ([`Span::UpTo`]), so the image is the same bits as one render of the same total
//! samples, however many passes it took, wherever it was interrupted and resumed. A stop request
//! (signal or time budget) is honoured at the next tile boundary; pixels of tiles not yet
//! rendered in that pass keep their earlier sums.
//!
//! Pass sizes: 1 spp first, then as many spp as fit in [`PASS_SECONDS`] at the measured speed
//! (at most double the previous pass; at most half the write interval and at most the time left),
//! never past the target; with a target and no budget, writes or error check, the second pass
//! goes straight to the target. Pass sizes change nothing in the bits.
//!
//! Adaptive sampling ([`Plan::adaptive`]): the target and the pass ends count the *mean* samples
//! per pixel. Every pixel first takes `warmup` samples; then each pass doubles the image's mean
//! (`warmup * 2^j`, the last pass ending at the target) and shares its samples out by
//! [`pass_targets`]. The schedule is fixed, not timed, because here pass boundaries do change the
//! bits: the same target gives the same image on any machine and thread count.
//!
//! A target error ([`Plan::target_error`]) ends the render at the first check point where the
//! estimated relative MSE is at most the target ([`check`]): uniform passes then end at every
//! power of two spp (never past it), adaptive ones check at every doubling of the mean.
pub mod bar;
pub mod check;

use crate::render::{render_span, Framebuffer, RenderOptions, Span};
use check::{clamp_to_check_point, CheckState, ErrorCheck};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};
use tessera_core::adaptive::{pass_targets, AdaptiveParams};
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;

/// Longest pass aimed for (seconds): short enough for a responsive stop and timely writes, long
/// enough that copying the sums between passes costs little.
pub const PASS_SECONDS: f64 = 10.0;

/// When to stop and when to write.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// Stop when every pixel has this many samples (`None`: no limit).
    pub target: Option<u64>,
    /// Stop when this much time has been spent in this run (`None`: no limit).
    pub budget: Option<Duration>,
    /// Call the writer after a pass when this much time has passed since the last write.
    pub write_every: Option<Duration>,
    /// Adaptive sampling: `target` is then the mean over pixels (see the module notes).
    pub adaptive: Option<AdaptiveParams>,
    /// Stop at the first check point where the estimated relative MSE is at most this.
    pub target_error: Option<f64>,
    /// Adaptive sampling resumed: the targets of the pass that was interrupted (one per pixel),
    /// finished before anything else.
    pub pending: Option<Vec<u64>>,
    /// A resumed render with a target error: its last check point, the first half of the next
    /// check.
    pub resumed_check: Option<CheckState>,
}

/// Why the passes ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ending {
    /// Every pixel reached the target.
    Target,
    /// The time budget ran out.
    Time,
    /// The stop flag was set from outside (a signal).
    Stopped,
    /// The estimated error reached [`Plan::target_error`].
    ErrorReached,
}

/// How the passes ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Why.
    pub ending: Ending,
    /// Passes completed in this run.
    pub passes: u64,
    /// The latest error estimate (with [`Plan::target_error`], from 16 spp on).
    pub estimate: Option<f64>,
    /// Adaptive sampling stopped inside a pass: that pass's targets, one per pixel (a checkpoint
    /// keeps them so that a resumed render finishes the same pass).
    pub pending: Option<Vec<u64>>,
    /// With [`Plan::target_error`]: the latest check point (a checkpoint keeps it).
    pub check: Option<CheckState>,
}

/// Where the render is, for a progress display.
#[derive(Clone, Copy, Debug)]
pub struct Status {
    /// Passes completed in this run.
    pub passes: u64,
    /// Fewest samples of any pixel at the start of the current pass.
    pub spp_low: u64,
    /// The current pass's end.
    pub pass_end: u64,
    /// Estimated samples per pixel done so far (fractional within the pass).
    pub spp_done: f64,
    /// Time spent in this run.
    pub elapsed: Duration,
    /// The latest error estimate (with [`Plan::target_error`]).
    pub estimate: Option<f64>,
}

/// Fewest and most samples (`count + dropped`) of any pixel.
pub fn spp_range(fb: &Framebuffer) -> (u64, u64) {
    fb.pixels
        .iter()
        .map(|p| p.count + p.dropped)
        .fold((u64::MAX, 0), |(lo, hi), n| (lo.min(n), hi.max(n)))
}

/// The writer's signature: `write(fb, passes_done, check_point)`, the last argument being the
/// latest check point of a render with a target error.
pub(crate) type Writer<'a> =
    dyn FnMut(&Framebuffer, u64, Option<&CheckState>) -> Result<(), String> + 'a;

/// Renders passes into `fb` (which may hold a resumed render) until `plan` says stop or `stop`
/// is set. `progress` is called as tiles arrive; `write` after each pass when the write interval
/// is due (its error ends the render). Returns why it ended, the passes completed and the last
/// error estimate.
pub fn run(
    job: &RenderJob,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    plan: &Plan,
    stop: &AtomicBool,
    progress: &mut dyn FnMut(&Status),
    write: &mut Writer,
) -> Result<Outcome, String> {
    let mut check = plan
        .target_error
        .map(|t| ErrorCheck::new(t, plan.resumed_check.clone()));
    let start = Instant::now();
    let deadline = plan.budget.map(|b| start + b);
    let time_up = AtomicBool::new(false);
    let finished = AtomicBool::new(false);
    std::thread::scope(|s| {
        if let Some(d) = deadline {
            // Watcher: the time budget stops the pass in flight at the next tile boundary.
            let (time_up, finished) = (&time_up, &finished);
            s.spawn(move || {
                while !finished.load(Ordering::SeqCst) {
                    let now = Instant::now();
                    if now >= d {
                        time_up.store(true, Ordering::SeqCst);
                        stop.store(true, Ordering::SeqCst);
                        return;
                    }
                    std::thread::sleep((d - now).min(Duration::from_millis(20)));
                }
            });
        }
        let mut pending = None;
        let out = passes(
            job,
            opts,
            fb,
            plan,
            deadline,
            stop,
            progress,
            write,
            start,
            &mut check,
            &mut pending,
        );
        finished.store(true, Ordering::SeqCst);
        out.map(|(e, passes)| Outcome {
            ending: match e {
                Ending::Stopped if time_up.load(Ordering::SeqCst) => Ending::Time,
                e => e,
            },
            passes,
            estimate: check.as_ref().and_then(|c| c.last),
            pending,
            check: check.as_ref().and_then(|c| c.state().cloned()),
        })
    })
}

#[allow(clippy::too_many_arguments)]
fn passes(
    job: &RenderJob,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    plan: &Plan,
    deadline: Option<Instant>,
    stop: &AtomicBool,
    progress: &mut dyn FnMut(&Status),
    write: &mut Writer,
    start: Instant,
    check: &mut Option<ErrorCheck>,
    pending: &mut Option<Vec<u64>>,
) -> Result<(Ending, u64), String> {
    if let Some(a) = &plan.adaptive {
        *pending = plan.pending.clone();
        return adaptive_passes(
            job, opts, fb, plan, a, stop, progress, write, start, check, pending,
        );
    }
    let target = plan.target.unwrap_or(u64::MAX);
    // With a target and nothing to pace (no time budget, no writes, no error check), the pass
    // after the first takes every pixel to the target: a pass's only other cost is copying
    // every tile's sums out of the framebuffer and back, and the first pass (1 spp) already
    // gives every pixel a value should the render be stopped.
    let unpaced = plan.target.is_some()
        && plan.write_every.is_none()
        && deadline.is_none()
        && check.is_none();
    let mut last_write = start;
    let mut next = 1u64;
    let mut rate = None::<f64>; // spp of the whole image per second
    let mut done = 0u64;
    loop {
        if stop.load(Ordering::SeqCst) {
            return Ok((Ending::Stopped, done));
        }
        let (low, _) = spp_range(fb);
        if check.as_ref().is_some_and(|c| c.reached(low)) {
            return Ok((Ending::ErrorReached, done));
        }
        if low >= target {
            return Ok((Ending::Target, done));
        }
        let mut budget = PASS_SECONDS;
        if let Some(w) = plan.write_every {
            budget = budget.min(w.as_secs_f64() / 2.0);
        }
        if let Some(d) = deadline {
            let left = d.saturating_duration_since(Instant::now()).as_secs_f64();
            if left <= 0.0 {
                return Ok((Ending::Time, done));
            }
            budget = budget.min(left);
            // Not even one more spp fits: stop between passes rather than cut one short.
            if rate.is_some_and(|r| r * left < 1.0) {
                return Ok((Ending::Time, done));
            }
        }
        if let Some(r) = rate {
            next = if unpaced {
                u64::MAX
            } else {
                ((r * budget) as u64).clamp(1, next.saturating_mul(2))
            };
        }
        let mut end = low.saturating_add(next).min(target);
        if check.is_some() {
            end = clamp_to_check_point(low, end);
        }
        let estimate = check.as_ref().and_then(|c| c.last);
        let t0 = Instant::now();
        let mut report = |d: usize, t: usize| {
            progress(&Status {
                passes: done,
                spp_low: low,
                pass_end: end,
                spp_done: low as f64 + (end - low) as f64 * d as f64 / t.max(1) as f64,
                elapsed: start.elapsed(),
                estimate,
            })
        };
        let complete =
            render_span::<NoProbe>(job, opts, fb, Span::UpTo(end), Some(stop), &mut report)
                .complete;
        if !complete {
            continue; // the stop flag is set: the loop's top returns
        }
        done += 1;
        let dt = t0.elapsed().as_secs_f64().max(1e-6);
        rate = Some((end - low) as f64 / dt);
        next = end - low;
        if let Some(c) = check.as_mut() {
            if end.is_power_of_two() && c.at(end, &fb.pixels) {
                return Ok((Ending::ErrorReached, done));
            }
        }
        let due = plan.write_every.is_some_and(|w| last_write.elapsed() >= w);
        if due && spp_range(fb).0 < target {
            write(fb, done, check.as_ref().and_then(|c| c.state()))?;
            last_write = Instant::now();
        }
    }
}

/// Samples taken so far (`count + dropped` over every pixel).
pub fn taken(fb: &Framebuffer) -> u64 {
    fb.pixels.iter().map(|p| p.count + p.dropped).sum()
}

/// [`passes`] with adaptive sampling: the fixed schedule of the module notes. The time budget
/// only stops a pass (at a tile boundary); it never changes a pass's size.
#[allow(clippy::too_many_arguments)]
fn adaptive_passes(
    job: &RenderJob,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    plan: &Plan,
    params: &AdaptiveParams,
    stop: &AtomicBool,
    progress: &mut dyn FnMut(&Status),
    write: &mut Writer,
    start: Instant,
    check: &mut Option<ErrorCheck>,
    pending: &mut Option<Vec<u64>>,
) -> Result<(Ending, u64), String> {
    let target = plan.target.unwrap_or(u64::MAX);
    let params = &params.for_integrator(job.integrator);
    // Samples every pixel takes before the first adaptive pass (never past the target).
    let first = params.warmup.max(1).min(target);
    let pixels = (fb.pixels.len() as u64).max(1);
    let mut last_write = start;
    let mut done = 0u64;
    loop {
        if stop.load(Ordering::SeqCst) {
            return Ok((Ending::Stopped, done));
        }
        let (low, _) = spp_range(fb);
        let mean = taken(fb) / pixels;
        if pending.is_none() && check.as_ref().is_some_and(|c| c.reached(mean)) {
            return Ok((Ending::ErrorReached, done));
        }
        if mean >= target && low >= first && pending.is_none() {
            return Ok((Ending::Target, done));
        }
        let warming = low < first && pending.is_none();
        let (from, end) = if let Some(t) = pending.as_ref() {
            // The interrupted pass: it ends at the mean its targets add up to.
            (mean, t.iter().sum::<u64>() / pixels)
        } else if warming {
            (low, first)
        } else {
            let mut end = params.warmup.max(1);
            while end <= mean {
                end = end.saturating_mul(2);
            }
            (mean, end.min(target))
        };
        let estimate = check.as_ref().and_then(|c| c.last);
        let mut report = |d: usize, t: usize| {
            progress(&Status {
                passes: done,
                spp_low: from,
                pass_end: end,
                spp_done: from as f64 + (end - from) as f64 * d as f64 / t.max(1) as f64,
                elapsed: start.elapsed(),
                estimate,
            })
        };
        let complete = if warming {
            // Per-pixel targets, as the passes have, so that the warm-up's rays are counted too
            // (the plans price samples by them).
            let targets = vec![first; fb.pixels.len()];
            let span = Span::Targets(&targets);
            render_span::<NoProbe>(job, opts, fb, span, Some(stop), &mut report).complete
        } else {
            let targets = match pending.take() {
                Some(t) => t,
                None => {
                    let budget = end.saturating_mul(pixels).saturating_sub(taken(fb));
                    pass_targets(&fb.pixels, fb.width, fb.height, budget, params)
                }
            };
            let span = Span::Targets(&targets);
            let complete =
                render_span::<NoProbe>(job, opts, fb, span, Some(stop), &mut report).complete;
            if !complete {
                *pending = Some(targets);
            }
            complete
        };
        if !complete {
            continue;
        }
        done += 1;
        // Every pass ends at the warm-up count or a doubling of the mean: each is a check point.
        if let Some(c) = check.as_mut() {
            if c.at(end, &fb.pixels) {
                return Ok((Ending::ErrorReached, done));
            }
        }
        let due = plan.write_every.is_some_and(|w| last_write.elapsed() >= w);
        if due && taken(fb) / pixels < target {
            write(fb, done, check.as_ref().and_then(|c| c.state()))?;
            last_write = Instant::now();
        }
    }
}

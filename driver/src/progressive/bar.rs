//! The progress bar of `tessera render`: passes, spp done / target, samples per second and ETA
//! (against the target spp, else against the time budget, else a spinner).
use super::Status;
use indicatif::{ProgressBar, ProgressStyle};
use std::time::Duration;

/// What the progress bar counts.
#[derive(Clone, Copy)]
pub enum BarMode {
    /// Samples (pixels x spp) against the target.
    Samples {
        /// Pixels rendered.
        pixels: u64,
        /// Samples per pixel aimed at.
        target: u64,
    },
    /// Milliseconds against the time budget.
    Time,
    /// Nothing to count against: a spinner.
    Spinner,
}

/// The bar (hidden with `quiet`) and what it counts.
pub fn progress_bar(
    quiet: bool,
    target: Option<u64>,
    budget: Option<Duration>,
    pixels: u64,
) -> (ProgressBar, BarMode) {
    let (len, template, mode) = match (target, budget) {
        (Some(t), _) => (
            t.saturating_mul(pixels),
            "{bar:40} {msg} spp, samples {per_sec}, eta {eta} ({elapsed_precise})",
            BarMode::Samples { pixels, target: t },
        ),
        (None, Some(b)) => (
            b.as_millis() as u64,
            "{bar:40} {msg} spp, time budget, eta {eta} ({elapsed_precise})",
            BarMode::Time,
        ),
        (None, None) => (
            0,
            "{spinner} {msg} spp ({elapsed_precise}); Ctrl-C to stop",
            BarMode::Spinner,
        ),
    };
    if quiet {
        return (ProgressBar::hidden(), mode);
    }
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    (bar, mode)
}

/// Shows `s`.
pub fn update_bar(bar: &ProgressBar, mode: BarMode, s: &Status) {
    let pass = match s.estimate {
        Some(e) => format!("{} (relMSE ~{e:.1e})", s.passes + 1),
        None => format!("{}", s.passes + 1),
    };
    match mode {
        BarMode::Samples { pixels, target } => {
            bar.set_message(format!("pass {pass}, {:.1}/{target}", s.spp_done));
            bar.set_position((s.spp_done * pixels as f64) as u64);
        }
        BarMode::Time => {
            bar.set_message(format!("pass {pass}, {:.1}", s.spp_done));
            bar.set_position(s.elapsed.as_millis() as u64);
        }
        BarMode::Spinner => {
            bar.set_message(format!("pass {pass}, {:.1}", s.spp_done));
            bar.tick();
        }
    }
}

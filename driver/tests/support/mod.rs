//! Helpers shared by the driver's integration tests (a directory, so Cargo does not build it as a
//! test of its own).
use std::sync::atomic::{AtomicBool, Ordering};
use tessera::progressive::{self, Job, Outcome, Plan};
use tessera::render::Framebuffer;

/// Runs `plan` into `fb` and requests a stop as soon as pass `pass` (counted from 0) is under way,
/// as a signal would; nothing is written on the way.
pub fn run_stopped_in_pass(job: Job, fb: &mut Framebuffer, plan: &Plan, pass: u64) -> Outcome {
    let stop = AtomicBool::new(false);
    progressive::run(
        job,
        fb,
        plan,
        &stop,
        &mut |s| {
            if s.passes == pass {
                stop.store(true, Ordering::SeqCst);
            }
        },
        &mut |_, _, _| Ok(()),
    )
    .expect("renders")
}

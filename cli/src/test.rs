//! `tessera test FILE.xml`: runs a Nori-style test file (`<test type="ttest">` with scenes or
//! BSDFs, `<test type="chi2test">` with BSDFs), one line per case, then `N passed, M failed`.
//! Exit codes: 0 all passed, 1 a case failed, 2 bad input (one located line on stderr).
use clap::Args;
use std::io::Write;
use std::path::PathBuf;
use tessera_lab::testfile::run_test_file;
use tessera_scene::error::InputError;

/// Arguments of `tessera test`.
#[derive(Args, Debug, Clone)]
pub struct TestArgs {
    /// The test file (`<test type="ttest">` or `<test type="chi2test">`).
    pub file: PathBuf,
    /// Seed of the random streams.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// Runs the command on the process's stdout and stderr; returns the exit code.
pub fn run(args: &TestArgs) -> i32 {
    let (out, err) = (std::io::stdout(), std::io::stderr());
    run_to(args, &mut out.lock(), &mut err.lock())
}

/// Runs the command writing the report to `out` and errors to `err` (so tests can read
/// them); returns the exit code (0 all passed, 1 a case failed, 2 bad input).
pub fn run_to(args: &TestArgs, out: &mut dyn Write, err: &mut dyn Write) -> i32 {
    let results = tessera_scene::xml::load_file(&args.file, &[]).and_then(|root| {
        run_test_file(&root, args.seed, |case| {
            // A closed stdout must not stop the tests; the exit code still tells.
            let _ = writeln!(out, "{case}");
            let _ = out.flush();
        })
    });
    match results {
        Err(e) => {
            let _ = writeln!(err, "error: {e}");
            InputError::EXIT_CODE
        }
        Ok(cases) => {
            let passed = cases.iter().filter(|c| c.passed()).count();
            let _ = writeln!(out, "{} passed, {} failed", passed, cases.len() - passed);
            i32::from(passed < cases.len())
        }
    }
}

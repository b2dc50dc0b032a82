//! `tessera test FILE.xml`: runs a Nori-style test file, one line per case, exit 1 on failure.
use crate::testfile::run_test_object;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `tessera test`.
#[derive(Args, Debug, Clone)]
pub struct TestArgs {
    /// The test file (`<test type="ttest">`).
    pub file: PathBuf,
    /// Seed of the random streams.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// Runs the command; returns the exit code (0 all passed, 1 a case failed, 2 bad input).
pub fn run(args: &TestArgs) -> i32 {
    let root = match crate::xml::load_file(&args.file, &[]) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    let results = run_test_object(&root, args.seed, |r| {
        println!(
            "{}: mean {:.6} vs reference {:.6}, p = {:.4} {}",
            r.label,
            r.mean,
            r.reference,
            r.test.p_value,
            if r.passed { "PASS" } else { "FAIL" }
        );
    });
    match results {
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
        Ok(rs) => {
            let passed = rs.iter().filter(|r| r.passed).count();
            println!("{} passed, {} failed", passed, rs.len() - passed);
            i32::from(passed < rs.len())
        }
    }
}

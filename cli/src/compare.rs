//! `tessera compare A B`: error measures of image A against the reference B, as text or JSON,
//! and optionally a false-colour difference image.
use clap::Args;
use std::path::PathBuf;
use tessera::image_io::read_image;
use tessera_lab::compare::compare;
use tessera_lab::compare::diff_image::write_diff;
use tessera_scene::error::InputError;

/// Arguments of `tessera compare`.
#[derive(Args, Debug, Clone)]
pub struct CompareArgs {
    /// The image to measure (.exr, .pfm, .png).
    pub a: PathBuf,
    /// The reference image (same size).
    pub b: PathBuf,
    /// Also write a false-colour PNG of the per-pixel relative error (log scale).
    #[arg(long, value_name = "PNG")]
    pub diff: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs the command; returns the exit code.
pub fn run(args: &CompareArgs) -> i32 {
    let usage = |msg: String| {
        eprintln!("error: {msg}");
        InputError::EXIT_CODE
    };
    let a = match read_image(&args.a) {
        Ok(i) => i,
        Err(e) => return usage(e),
    };
    let b = match read_image(&args.b) {
        Ok(i) => i,
        Err(e) => return usage(e),
    };
    let c = match compare(&a, &b) {
        Ok(c) => c,
        Err(e) => {
            return usage(format!(
                "{} and {}: {e}",
                args.a.display(),
                args.b.display()
            ))
        }
    };
    let names = (args.a.display().to_string(), args.b.display().to_string());
    let names = (names.0.as_str(), names.1.as_str());
    if args.json {
        print!("{}", c.to_json(names));
    } else {
        print!("{}", c.to_text(names));
    }
    if let Some(d) = &args.diff {
        if let Err(e) = write_diff(d, &a, &b) {
            eprintln!("error: {e}");
            return 1;
        }
    }
    0
}

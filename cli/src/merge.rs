//! `tessera merge`: assemble part files (from `tessera render --crop/--tiles/--sample-range`)
//! into one image.
use clap::Args;
use std::path::PathBuf;
use tessera::image_io::{write_image, Format, RgbImage};
use tessera::split::merge::merge_parts;
use tessera::split::{read_part, write_part, PartInfo, PixelSelection};
use tessera_scene::error::InputError;

/// Arguments of `tessera merge`.
#[derive(Args, Debug, Clone)]
pub struct MergeArgs {
    /// Part files (.exr written by a split `tessera render`), in any order.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output image; the extension picks the format (.exr, .pfm, .png). May be repeated.
    #[arg(short = 'o', long = "output", required = true)]
    pub outputs: Vec<PathBuf>,
    /// Write pixels that no part holds as black instead of failing.
    #[arg(long)]
    pub allow_missing: bool,
    /// Write the EXR outputs as a part of the whole image (exact sums and settings kept), so the
    /// result can be merged again, e.g. with later sample ranges. Needs every pixel covered.
    #[arg(long)]
    pub as_part: bool,
    /// No summary line.
    #[arg(short, long)]
    pub quiet: bool,
}

fn usage(msg: String) -> i32 {
    eprintln!("error: {msg}");
    InputError::EXIT_CODE
}

/// Runs the command; returns the exit code.
pub fn run(args: &MergeArgs) -> i32 {
    for o in &args.outputs {
        if Format::from_path(o).is_none() {
            return usage(format!(
                "{}: unknown output format (use .exr, .pfm or .png)",
                o.display()
            ));
        }
    }
    let mut parts = Vec::with_capacity(args.parts.len());
    for p in &args.parts {
        match read_part(p) {
            Ok(part) => parts.push((p.display().to_string(), part)),
            Err(e) => return usage(e),
        }
    }
    let merged = match merge_parts(&parts, args.allow_missing) {
        Ok(m) => m,
        Err(e) => return usage(e),
    };
    let img = RgbImage {
        width: merged.fb.width,
        height: merged.fb.height,
        data: merged.fb.rgb(),
    };
    let part_info = if args.as_part {
        if merged.missing > 0 {
            return usage(format!(
                "--as-part needs every pixel: {} pixels are in no part",
                merged.missing
            ));
        }
        let first = &parts[0].1.info;
        Some(PartInfo {
            selection: PixelSelection::All,
            samples: merged.samples.clone(),
            ..first.clone()
        })
    } else {
        None
    };
    let mut code = 0;
    for o in &args.outputs {
        let written = match &part_info {
            Some(info) if Format::from_path(o) == Some(Format::Exr) => {
                write_part(o, info, &merged.fb)
            }
            _ => write_image(o, &img),
        };
        if let Err(e) = written {
            eprintln!("error: {e}");
            code = 1;
        }
    }
    if !args.quiet || code != 0 {
        eprintln!(
            "merged {} parts: {}x{}, samples {}..{}, {} pixels missing; {} non-finite samples dropped",
            parts.len(),
            img.width,
            img.height,
            merged.samples.start,
            merged.samples.end,
            merged.missing,
            merged.fb.dropped()
        );
    }
    code
}

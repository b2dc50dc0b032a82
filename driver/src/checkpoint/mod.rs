//! Render checkpoints: the accumulated sums of every pixel plus what identifies the render, so
//! that `tessera render --resume FILE` continues exactly where a render stopped.
//!
//! # File format (version 6, all integers and floats little-endian)
//!
//! | offset | size | field |
//! |---|---|---|
//! | 0 | 8 | magic `TESSCKPT` |
//! | 8 | 4 | format version, u32 = 6 (1 to 5 are still read) |
//! | 12 | 4 | image width, u32 >= 1 |
//! | 16 | 4 | image height, u32 >= 1 |
//! | 20 | 8 | seed, u64 |
//! | 28 | 8 | target samples per pixel, u64 (0 = none: a time budget or "until interrupted") |
//! | 36 | 8 | scene hash, u64 ([`scene_hash`]) |
//! | 44 | 8 | passes rendered so far, u64 |
//! | 52 | 8 | render seconds so far, f64 (finite, >= 0) |
//! | 60 | 4 | integrator description length `n`, u32 <= 4096 |
//! | 64 | n | integrator description, UTF-8 (its name and every parameter) |
//! | 64+n | 72 per pixel | row-major pixels: `sum` 3 x f64, `sum_sq` 3 x f64, `count` u64, `dropped` u64, `rays` u64 (version 5; 64 bytes without `rays` before) |
//! | 64+n+72p | 8 | `k`, u64: 0, or the pixel count `p` when a pass was interrupted (version 2) |
//! | 72+n+72p | 8 per pixel if `k > 0` | the interrupted adaptive pass's target per pixel, u64 >= `count + dropped` (version 2) |
//! | t | 8 | `c`, u64: 0, or the pixel count `p` when a render with a target error has passed a check point (version 3) |
//! | t+8 | 8 if `c > 0` | the check point's samples per pixel, u64 >= 1 |
//! | t+16 | 8 if `c > 0` | the estimate made there, f64 (NaN: none) |
//! | t+24 | 72 per pixel if `c > 0` | every pixel's accumulators at the check point, as above, each at most the pixel's current count |
//! | u | 8 | `s`, u64: 0, or the floats per pixel of the splatted sums when the render splats (version 4) |
//! | u+8 | 4 s per pixel | row-major, every pixel's splatted sums, f32 (`driver/src/splats.rs`) |
//! | end-16 | 8 | the samples per pixel the sampler was set up for, u64 (zsobol's pixel blocks; 0: the scene's own set-up) (version 6) |
//! | end-8 | 8 | FNV-1a 64 of every byte before it |
//!
//! A pixel has taken `count + dropped` samples, indices `0..count + dropped`; a resumed render
//! continues each pixel from its own count, so the result is the same bits as one uninterrupted
//! render. An adaptive pass decides every pixel's target from the image at its start, so when one
//! is interrupted its targets are saved, and the resumed render first finishes them. A render with
//! a target error (`--target-error`) estimates its error at each doubling of the samples from the
//! state at the previous one ([`crate::progressive::check`]), so that state is saved too, and the
//! resumed render checks (and stops) where the uninterrupted one would. A render that splats its
//! samples saves every pixel's splatted sums exactly, since its image is made from them. Version
//! 1 files (no targets section), version 2 files (no check point section), version 3 files
//! (no splatted sums) and version 4 files (no ray counts: read as 0) are still read. The reader checks the total length against the header
//! before allocating anything,
//! then the checksum, then every value (finite sums, no count overflow): a truncated, corrupted
//! or hostile file gives an error, never a panic or a huge allocation.
//!
//! FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3) is written down here so the
//! hashes stay the same across Rust versions (std's `DefaultHasher` promises no such thing).
mod read;
mod write;

pub use read::{load_checkpoint, read_checkpoint};
pub use tessera_scene::hash::{scene_hash, Fnv1a};
pub use write::write_checkpoint;

use crate::progressive::check::CheckState;
use crate::splats::Splats;
use tessera_core::film::PixelAccum;

/// The file's first 8 bytes.
pub const MAGIC: [u8; 8] = *b"TESSCKPT";
/// The format version this build writes (it also reads versions 1 to 5).
pub(crate) const VERSION: u32 = 6;
/// Longest integrator description accepted.
pub(crate) const MAX_DESCRIPTION: usize = 4096;
const HEADER: usize = 64;
const PIXEL: usize = 8 * PixelAccum::WORDS;

/// Bytes of a pixel record in a file of format `version` (no ray count before version 5).
fn pixel_bytes(version: u32) -> usize {
    match version {
        1..=4 => PIXEL - 8,
        _ => PIXEL,
    }
}

/// What identifies a render, plus how far it got.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckpointMeta {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Seed of every random stream.
    pub seed: u64,
    /// Target samples per pixel (0 = none).
    pub target_spp: u64,
    /// [`scene_hash`] of the scene file and defines.
    pub scene_hash: u64,
    /// Passes rendered so far.
    pub passes: u64,
    /// Seconds spent rendering so far.
    pub seconds: f64,
    /// The integrator and its parameters, as text.
    pub integrator: String,
    /// The samples per pixel the sampler was set up for (zsobol's pixel blocks follow it), which
    /// a resumed render keeps; 0 for the scene's own set-up (its `sample_count`), as in files
    /// written before it was saved.
    pub sampler_spp: u64,
}

impl CheckpointMeta {
    /// Whether a checkpoint (`self`) belongs to the render described by `now`: same scene,
    /// size, seed and integrator. The error is one line saying what differs.
    pub fn matches(&self, now: &CheckpointMeta) -> Result<(), String> {
        if self.scene_hash != now.scene_hash {
            return Err(format!(
                "the checkpoint is for another scene file or -D defines (scene hash {:016x}, this scene {:016x})",
                self.scene_hash, now.scene_hash
            ));
        }
        if (self.width, self.height) != (now.width, now.height) {
            return Err(format!(
                "the checkpoint is {}x{}, this render {}x{}",
                self.width, self.height, now.width, now.height
            ));
        }
        if self.seed != now.seed {
            return Err(format!(
                "the checkpoint has seed {}, this render {}",
                self.seed, now.seed
            ));
        }
        if self.integrator != now.integrator {
            return Err(format!(
                "the checkpoint's integrator is {}, this render's {}",
                self.integrator, now.integrator
            ));
        }
        Ok(())
    }
}

/// A checkpoint read back.
#[derive(Clone, Debug, PartialEq)]
pub struct Checkpoint {
    /// Identification and progress.
    pub meta: CheckpointMeta,
    /// Every pixel's sums, row-major.
    pub pixels: Vec<PixelAccum>,
    /// The targets of an interrupted adaptive pass, one per pixel.
    pub pending: Option<Vec<u64>>,
    /// The last check point of a render with a target error.
    pub check: Option<CheckState>,
    /// Every pixel's splatted sums, row-major, when the render splats its samples.
    pub splats: Option<Vec<f32>>,
}

/// What a checkpoint keeps besides the identification and the pixels: how the render goes on.
#[derive(Clone, Copy, Debug, Default)]
pub struct Continuation<'a> {
    /// The targets of an interrupted adaptive pass, one per pixel.
    pub pending: Option<&'a [u64]>,
    /// The last check point of a render with a target error.
    pub check: Option<&'a CheckState>,
    /// Every pixel's splatted sums, when the render splats its samples.
    pub splats: Option<&'a Splats>,
}

#[cfg(test)]
mod tests;

//! Reading a checkpoint back, checking everything (the format is in the parent module's notes).
use super::{
    pixel_bytes, Checkpoint, CheckpointMeta, Fnv1a, HEADER, MAGIC, MAX_DESCRIPTION, VERSION,
};
use crate::progressive::check::CheckState;
use std::path::Path;
use tessera_core::film::PixelAccum;

/// Reads a checkpoint file; errors name the file (one line).
pub fn load_checkpoint(path: &Path) -> Result<Checkpoint, String> {
    let bytes = std::fs::read(path)
        .map_err(|e| format!("{}: cannot read checkpoint: {e}", path.display()))?;
    read_checkpoint(&bytes).map_err(|e| format!("{}: bad checkpoint: {e}", path.display()))
}

/// Little-endian field reader over a slice whose length was already checked.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn take<const N: usize>(&mut self) -> [u8; N] {
        let mut out = [0u8; N];
        out.copy_from_slice(&self.bytes[self.at..self.at + N]);
        self.at += N;
        out
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes(self.take())
    }
    fn u64(&mut self) -> u64 {
        u64::from_le_bytes(self.take())
    }
}

/// The u64 at byte `at` of `bytes`, if the file holds it (`None` for an offset past the end or
/// one that overflowed).
fn u64_at(bytes: &[u8], at: Option<u64>) -> Option<u64> {
    let at = usize::try_from(at?).ok()?;
    let b = bytes.get(at..at.checked_add(8)?)?;
    Some(u64::from_le_bytes(std::array::from_fn(|i| b[i])))
}

/// Parses and checks a checkpoint held in memory (the fuzzing entry point).
pub fn read_checkpoint(bytes: &[u8]) -> Result<Checkpoint, String> {
    if bytes.len() < HEADER + 8 {
        return Err(format!(
            "file is {} bytes, shorter than any checkpoint (truncated?)",
            bytes.len()
        ));
    }
    if bytes[..8] != MAGIC {
        return Err("not a Tessera checkpoint (wrong magic bytes)".into());
    }
    let mut c = Cursor { bytes, at: 8 };
    let version = c.u32();
    if !(1..=VERSION).contains(&version) {
        return Err(format!(
            "format version {version}, this build reads versions 1 to {VERSION}"
        ));
    }
    let width = c.u32();
    let height = c.u32();
    let (seed, target_spp, scene_hash, passes) = (c.u64(), c.u64(), c.u64(), c.u64());
    let seconds = f64::from_bits(c.u64());
    let n = c.u32() as usize;
    if width == 0 || height == 0 {
        return Err(format!("image size {width}x{height}"));
    }
    if n > MAX_DESCRIPTION {
        return Err(format!(
            "integrator description of {n} bytes (at most {MAX_DESCRIPTION})"
        ));
    }
    let count = width as u64 * height as u64;
    let records = |k: u64, size: u64| k.checked_mul(size);
    let add = |a: Option<u64>, b: Option<u64>| a?.checked_add(b?);
    // The sections' lengths, walked through the counts they start with (each read bounds
    // checked; a count that is neither 0 nor the pixel count is refused after the checksum).
    let pixel = pixel_bytes(version);
    let pixels_end = add(Some((HEADER + n) as u64), records(count, pixel as u64));
    let targets = match version {
        1 => 0,
        _ => u64_at(bytes, pixels_end).unwrap_or(0),
    };
    let targets_end = match version {
        1 => pixels_end,
        _ => add(add(pixels_end, Some(8)), records(targets, 8)),
    };
    let checks = match version {
        1 | 2 => 0,
        _ => u64_at(bytes, targets_end).unwrap_or(0),
    };
    let checks_end = match (version, checks) {
        (1 | 2, _) => targets_end,
        (_, 0) => add(targets_end, Some(8)),
        (_, k) => add(add(targets_end, Some(24)), records(k, pixel as u64)),
    };
    let stride = match version {
        1..=3 => 0,
        _ => u64_at(bytes, checks_end).unwrap_or(0),
    };
    let splats_end = match version {
        1..=3 => checks_end,
        _ => add(
            add(checks_end, Some(8)),
            records(count, 4).and_then(|b| records(b, stride)),
        ),
    };
    let sampler_end = match version {
        1..=5 => splats_end,
        _ => add(splats_end, Some(8)),
    };
    let expected = add(sampler_end, Some(8));
    if expected != Some(bytes.len() as u64) {
        return Err(format!(
            "file is {} bytes, a {width}x{height} checkpoint takes {} (truncated or corrupted)",
            bytes.len(),
            expected.map_or("more".to_string(), |e| e.to_string())
        ));
    }
    let body = bytes.len() - 8;
    let mut h = Fnv1a::default();
    h.update(&bytes[..body]);
    let stored = u64::from_le_bytes(bytes[body..].try_into().map_err(|_| "checksum")?);
    if h.0 != stored {
        return Err("checksum mismatch (corrupted)".into());
    }
    if !(seconds.is_finite() && seconds >= 0.0) {
        return Err(format!("render time {seconds}"));
    }
    let integrator = std::str::from_utf8(&bytes[HEADER..HEADER + n])
        .map_err(|_| "integrator description is not UTF-8".to_string())?
        .to_string();
    if targets != 0 && targets != count {
        return Err(format!(
            "{targets} pass targets for {count} pixels (corrupted)"
        ));
    }
    if checks != 0 && checks != count {
        return Err(format!(
            "a check point of {checks} pixels for {count} (corrupted)"
        ));
    }
    c.at = HEADER + n;
    let count = count as usize;
    let pixels = read_pixels(&mut c, pixel, count, width as usize, "pixel", |_| u64::MAX)?;
    let taken = |i: usize| pixels[i].count + pixels[i].dropped;
    let pending = if targets == 0 {
        None
    } else {
        c.at += 8;
        let t: Vec<u64> = (0..count).map(|_| c.u64()).collect();
        if let Some(i) = (0..count).find(|&i| t[i] < taken(i)) {
            let (x, y) = (i % width as usize, i / width as usize);
            return Err(format!(
                "pixel ({x}, {y}) has a pass target below its sample count"
            ));
        }
        Some(t)
    };
    if version >= 2 && targets == 0 {
        c.at += 8;
    }
    let check = if checks == 0 {
        None
    } else {
        c.at += 8;
        let spp = c.u64();
        let estimate = f64::from_bits(c.u64());
        if spp == 0 || !(estimate.is_nan() || (estimate.is_finite() && estimate >= 0.0)) {
            return Err(format!(
                "check point at {spp} spp with estimate {estimate} (corrupted)"
            ));
        }
        let before = read_pixels(
            &mut c,
            pixel,
            count,
            width as usize,
            "check point pixel",
            taken,
        )?;
        Some(CheckState {
            spp,
            estimate: (!estimate.is_nan()).then_some(estimate),
            pixels: before,
        })
    };
    if version >= 3 && checks == 0 {
        c.at += 8;
    }
    let splats = if stride == 0 {
        None
    } else {
        c.at += 8;
        let sums: Vec<f32> = (0..count as u64 * stride)
            .map(|_| f32::from_le_bytes(c.take()))
            .collect();
        if let Some(i) = sums.iter().position(|v| !v.is_finite()) {
            let i = i / stride as usize;
            let (x, y) = (i % width as usize, i / width as usize);
            return Err(format!("pixel ({x}, {y}) holds impossible splatted sums"));
        }
        Some(sums)
    };
    if version >= 4 && stride == 0 {
        c.at += 8;
    }
    let sampler_spp = match version {
        1..=5 => 0,
        _ => c.u64(),
    };
    Ok(Checkpoint {
        meta: CheckpointMeta {
            width,
            height,
            seed,
            target_spp,
            scene_hash,
            passes,
            seconds,
            integrator,
            sampler_spp,
        },
        pixels,
        pending,
        check,
        splats,
    })
}

/// `count` pixel records of `bytes` each at the cursor (without the ray count when shorter than
/// [`PixelAccum::WORDS`] words), each checked: finite sums, no count overflow, and at most
/// `most(i)` samples for pixel `i` (errors call a pixel `what`).
fn read_pixels(
    c: &mut Cursor,
    bytes: usize,
    count: usize,
    width: usize,
    what: &str,
    most: impl Fn(usize) -> u64,
) -> Result<Vec<PixelAccum>, String> {
    let mut pixels = Vec::with_capacity(count);
    for i in 0..count {
        let p =
            PixelAccum::from_words(std::array::from_fn(
                |k| {
                    if k < bytes / 8 {
                        c.u64()
                    } else {
                        0
                    }
                },
            ));
        let finite = p.sum.iter().chain(&p.sum_sq).all(|v| v.is_finite());
        let taken = p.count.checked_add(p.dropped);
        if !finite || p.sum_sq.iter().any(|v| *v < 0.0) || taken.is_none_or(|t| t > most(i)) {
            let (x, y) = (i % width, i / width);
            return Err(format!("{what} ({x}, {y}) holds impossible sums"));
        }
        pixels.push(p);
    }
    Ok(pixels)
}

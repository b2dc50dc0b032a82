//! Writing a checkpoint (the format is in the parent module's notes).
use super::{CheckpointMeta, Continuation, Fnv1a, MAGIC, MAX_DESCRIPTION, PIXEL, VERSION};
use crate::image_io::write_atomic;
use std::io::{BufWriter, Write};
use std::path::Path;
use tessera_core::film::PixelAccum;

/// Writes `meta`, `pixels` and `more` (the targets of an interrupted adaptive pass, the last
/// check point) to `path` atomically (a temporary file in the same directory, synced, then
/// renamed).
pub fn write_checkpoint(
    path: &Path,
    meta: &CheckpointMeta,
    pixels: &[PixelAccum],
    more: Continuation,
) -> Result<(), String> {
    write_atomic(path, |tmp| {
        write_to(tmp, meta, pixels, more).map_err(|e| e.to_string())
    })
    .map_err(|e| format!("{}: cannot write checkpoint: {e}", path.display()))
}

/// A writer that hashes what passes through it.
struct Hashing<W: Write> {
    inner: W,
    hash: Fnv1a,
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.update(&buf[..n]);
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

fn write_to(
    path: &Path,
    meta: &CheckpointMeta,
    pixels: &[PixelAccum],
    more: Continuation,
) -> std::io::Result<()> {
    let pending = more.pending;
    let bad = |m: &str| std::io::Error::new(std::io::ErrorKind::InvalidInput, m.to_string());
    if pixels.len() != meta.width as usize * meta.height as usize {
        return Err(bad("pixel count does not match the size"));
    }
    if pending.is_some_and(|t| t.len() != pixels.len()) {
        return Err(bad("pass targets do not match the size"));
    }
    if more.check.is_some_and(|c| c.pixels.len() != pixels.len()) {
        return Err(bad("check point does not match the size"));
    }
    if more
        .splats
        .is_some_and(|s| s.sums.len() != pixels.len() * s.stride())
    {
        return Err(bad("splatted sums do not match the size"));
    }
    if meta.integrator.len() > MAX_DESCRIPTION {
        return Err(bad("integrator description too long"));
    }
    let file = std::fs::File::create(path)?;
    let mut w = Hashing {
        inner: BufWriter::with_capacity(1 << 20, file),
        hash: Fnv1a::default(),
    };
    w.write_all(&MAGIC)?;
    w.write_all(&VERSION.to_le_bytes())?;
    w.write_all(&meta.width.to_le_bytes())?;
    w.write_all(&meta.height.to_le_bytes())?;
    for v in [meta.seed, meta.target_spp, meta.scene_hash, meta.passes] {
        w.write_all(&v.to_le_bytes())?;
    }
    w.write_all(&meta.seconds.to_le_bytes())?;
    w.write_all(&(meta.integrator.len() as u32).to_le_bytes())?;
    w.write_all(meta.integrator.as_bytes())?;
    write_pixels(&mut w, pixels)?;
    let targets = pending.unwrap_or(&[]);
    w.write_all(&(targets.len() as u64).to_le_bytes())?;
    for t in targets {
        w.write_all(&t.to_le_bytes())?;
    }
    match more.check {
        None => w.write_all(&0u64.to_le_bytes())?,
        Some(c) => {
            w.write_all(&(c.pixels.len() as u64).to_le_bytes())?;
            w.write_all(&c.spp.to_le_bytes())?;
            w.write_all(&c.estimate.unwrap_or(f64::NAN).to_le_bytes())?;
            write_pixels(&mut w, &c.pixels)?;
        }
    }
    match more.splats {
        None => w.write_all(&0u64.to_le_bytes())?,
        Some(s) => {
            w.write_all(&(s.stride() as u64).to_le_bytes())?;
            let mut buf = Vec::with_capacity(4 * s.stride());
            for pixel in s.sums.chunks(s.stride()) {
                buf.clear();
                buf.extend(pixel.iter().flat_map(|v| v.to_le_bytes()));
                w.write_all(&buf)?;
            }
        }
    }
    w.write_all(&meta.sampler_spp.to_le_bytes())?;
    let sum = w.hash.0;
    let mut inner = w.inner;
    inner.write_all(&sum.to_le_bytes())?;
    inner.into_inner().map_err(|e| e.into_error())?.sync_all()
}

/// Every pixel's record ([`PixelAccum::to_words`], little-endian).
fn write_pixels(w: &mut impl Write, pixels: &[PixelAccum]) -> std::io::Result<()> {
    let mut rec = [0u8; PIXEL];
    for p in pixels {
        for (i, v) in p.to_words().iter().enumerate() {
            rec[i * 8..i * 8 + 8].copy_from_slice(&v.to_le_bytes());
        }
        w.write_all(&rec)?;
    }
    Ok(())
}

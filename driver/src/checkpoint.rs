//! Render checkpoints: the accumulated sums of every pixel plus what identifies the render, so
//! that `tessera render --resume FILE` continues exactly where a render stopped.
//!
//! # File format (version 2, all integers and floats little-endian)
//!
//! | offset | size | field |
//! |---|---|---|
//! | 0 | 8 | magic `TESSCKPT` |
//! | 8 | 4 | format version, u32 = 1 |
//! | 12 | 4 | image width, u32 >= 1 |
//! | 16 | 4 | image height, u32 >= 1 |
//! | 20 | 8 | seed, u64 |
//! | 28 | 8 | target samples per pixel, u64 (0 = none: a time budget or "until interrupted") |
//! | 36 | 8 | scene hash, u64 ([`scene_hash`]) |
//! | 44 | 8 | passes rendered so far, u64 |
//! | 52 | 8 | render seconds so far, f64 (finite, >= 0) |
//! | 60 | 4 | integrator description length `n`, u32 <= 4096 |
//! | 64 | n | integrator description, UTF-8 (its name and every parameter) |
//! | 64+n | 64 per pixel | row-major pixels: `sum` 3 x f64, `sum_sq` 3 x f64, `count` u64, `dropped` u64 |
//! | 64+n+64p | 8 | `k`, u64: 0, or the pixel count `p` when a pass was interrupted (version 2) |
//! | 72+n+64p | 8 per pixel if `k > 0` | the interrupted adaptive pass's target per pixel, u64 >= `count + dropped` (version 2) |
//! | end-8 | 8 | FNV-1a 64 of every byte before it |
//!
//! A pixel has taken `count + dropped` samples, indices `0..count + dropped`; a resumed render
//! continues each pixel from its own count, so the result is the same bits as one uninterrupted
//! render. An adaptive pass decides every pixel's target from the image at its start, so when one
//! is interrupted its targets are saved, and the resumed render first finishes them. Version 1
//! files (no targets section) are still read. The reader checks the total length against the header before allocating anything,
//! then the checksum, then every value (finite sums, no count overflow): a truncated, corrupted
//! or hostile file gives an error, never a panic or a huge allocation.
//!
//! FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3) is written down here so the
//! hashes stay the same across Rust versions (std's `DefaultHasher` promises no such thing).
use crate::image_io::write_atomic;
use std::io::{BufWriter, Write};
use std::path::Path;
use tessera_core::film::PixelAccum;

/// The file's first 8 bytes.
pub const MAGIC: [u8; 8] = *b"TESSCKPT";
/// The format version this build writes (it also reads version 1).
pub const VERSION: u32 = 2;
/// Longest integrator description accepted.
pub const MAX_DESCRIPTION: usize = 4096;
const HEADER: usize = 64;
const PIXEL: usize = 64;

/// FNV-1a 64, fed in pieces.
#[derive(Clone, Copy, Debug)]
pub struct Fnv1a(pub u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv1a {
    /// Adds bytes.
    pub fn update(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
}

/// The hash identifying a scene: FNV-1a 64 over the scene file's bytes, then each `-D` define
/// (the last value given for a name wins; names in byte order), each string preceded by its
/// length as u64 LE. Files the scene references (meshes, textures, includes) are not hashed.
pub fn scene_hash(scene_bytes: &[u8], defines: &[(String, String)]) -> u64 {
    let mut last: std::collections::BTreeMap<&str, &str> = Default::default();
    for (k, v) in defines {
        last.insert(k, v);
    }
    let mut h = Fnv1a::default();
    let mut put = |b: &[u8]| {
        h.update(&(b.len() as u64).to_le_bytes());
        h.update(b);
    };
    put(scene_bytes);
    for (k, v) in last {
        put(k.as_bytes());
        put(v.as_bytes());
    }
    h.0
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
}

/// Writes `meta`, `pixels` and the targets of an interrupted adaptive pass (`pending`, one per
/// pixel) to `path` atomically (a temporary file in the same directory, synced, then renamed).
pub fn write_checkpoint(
    path: &Path,
    meta: &CheckpointMeta,
    pixels: &[PixelAccum],
    pending: Option<&[u64]>,
) -> Result<(), String> {
    write_atomic(path, |tmp| {
        write_to(tmp, meta, pixels, pending).map_err(|e| e.to_string())
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
    pending: Option<&[u64]>,
) -> std::io::Result<()> {
    let bad = |m: &str| std::io::Error::new(std::io::ErrorKind::InvalidInput, m.to_string());
    if pixels.len() != meta.width as usize * meta.height as usize {
        return Err(bad("pixel count does not match the size"));
    }
    if pending.is_some_and(|t| t.len() != pixels.len()) {
        return Err(bad("pass targets do not match the size"));
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
    let mut rec = [0u8; PIXEL];
    for p in pixels {
        for (i, v) in p.to_words().iter().enumerate() {
            rec[i * 8..i * 8 + 8].copy_from_slice(&v.to_le_bytes());
        }
        w.write_all(&rec)?;
    }
    let targets = pending.unwrap_or(&[]);
    w.write_all(&(targets.len() as u64).to_le_bytes())?;
    for t in targets {
        w.write_all(&t.to_le_bytes())?;
    }
    let sum = w.hash.0;
    let mut inner = w.inner;
    inner.write_all(&sum.to_le_bytes())?;
    inner.into_inner().map_err(|e| e.into_error())?.sync_all()
}

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
    if version != 1 && version != VERSION {
        return Err(format!(
            "format version {version}, this build reads versions 1 and {VERSION}"
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
    let pixels_end = count
        .checked_mul(PIXEL as u64)
        .and_then(|p| p.checked_add((HEADER + n) as u64));
    // Version 2: the targets count follows the pixels; it is read (bounds checked) to know the
    // length, and checked against the pixel count after the checksum.
    let targets = match (version, pixels_end) {
        (1, _) | (_, None) => 0,
        (_, Some(end)) => usize::try_from(end)
            .ok()
            .and_then(|e| bytes.get(e..e.checked_add(8)?))
            .map_or(0, |b| u64::from_le_bytes(std::array::from_fn(|i| b[i]))),
    };
    let section = if version == 1 { 0 } else { 8 };
    let expected = pixels_end
        .and_then(|e| e.checked_add(section + 8))
        .and_then(|e| targets.checked_mul(8).and_then(|t| e.checked_add(t)));
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
    c.at = HEADER + n;
    let count = count as usize;
    let mut pixels = Vec::with_capacity(count);
    for i in 0..count {
        let p = PixelAccum::from_words(std::array::from_fn(|_| c.u64()));
        let finite = p.sum.iter().chain(&p.sum_sq).all(|v| v.is_finite());
        if !finite || p.sum_sq.iter().any(|v| *v < 0.0) || p.count.checked_add(p.dropped).is_none()
        {
            let (x, y) = (i % width as usize, i / width as usize);
            return Err(format!("pixel ({x}, {y}) holds impossible sums"));
        }
        pixels.push(p);
    }
    let pending = if targets == 0 {
        None
    } else {
        c.at += 8;
        let t: Vec<u64> = (0..count).map(|_| c.u64()).collect();
        if let Some(i) = (0..count).find(|&i| t[i] < pixels[i].count + pixels[i].dropped) {
            let (x, y) = (i % width as usize, i / width as usize);
            return Err(format!(
                "pixel ({x}, {y}) has a pass target below its sample count"
            ));
        }
        Some(t)
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
        },
        pixels,
        pending,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_reference_values() {
        // Published FNV-1a 64 test vectors.
        let mut h = Fnv1a::default();
        h.update(b"");
        assert_eq!(h.0, 0xcbf29ce484222325);
        h.update(b"a");
        assert_eq!(h.0, 0xaf63dc4c8601ec8c);
        let mut h = Fnv1a::default();
        h.update(b"foobar");
        assert_eq!(h.0, 0x85944171f73967e8);
    }

    #[test]
    fn defines_order_does_not_matter_but_values_do() {
        let d = |v: &[(&str, &str)]| -> Vec<(String, String)> {
            v.iter()
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect()
        };
        let a = scene_hash(b"x", &d(&[("a", "1"), ("b", "2")]));
        assert_eq!(a, scene_hash(b"x", &d(&[("b", "2"), ("a", "1")])));
        assert_ne!(a, scene_hash(b"x", &d(&[("a", "1"), ("b", "3")])));
        assert_ne!(a, scene_hash(b"y", &d(&[("a", "1"), ("b", "2")])));
        // Length prefixes: moving a byte between name and value changes the hash.
        assert_ne!(
            scene_hash(b"", &d(&[("ab", "c")])),
            scene_hash(b"", &d(&[("a", "bc")]))
        );
    }

    #[test]
    fn round_trip_and_every_damage_is_caught() {
        let meta = CheckpointMeta {
            width: 3,
            height: 2,
            seed: 7,
            target_spp: 16,
            scene_hash: 0x1234,
            passes: 3,
            seconds: 1.5,
            integrator: "Path(max_depth: 8)".into(),
        };
        let pixels: Vec<PixelAccum> = (0..6)
            .map(|i| PixelAccum {
                sum: [i as f64, 0.5, 1e300],
                sum_sq: [1.0, 2.0, 3.0],
                count: i,
                dropped: 1,
            })
            .collect();
        let path = std::env::temp_dir().join(format!("tessera-ckpt-{}.bin", std::process::id()));
        let targets: Vec<u64> = (0..6).map(|i| 2 * i + 1).collect();
        write_checkpoint(&path, &meta, &pixels, Some(&targets)).unwrap();
        let with_targets = std::fs::read(&path).unwrap();
        write_checkpoint(&path, &meta, &pixels, None).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        let back = read_checkpoint(&bytes).unwrap();
        assert_eq!(back.meta, meta);
        assert_eq!(back.pixels, pixels);
        assert_eq!(back.pending, None);
        let back = read_checkpoint(&with_targets).unwrap();
        assert_eq!((back.meta, back.pixels), (meta.clone(), pixels.clone()));
        assert_eq!(back.pending.as_deref(), Some(&targets[..]));
        // Version 1 (no targets section) is still read.
        let mut v1 = bytes[..bytes.len() - 16].to_vec();
        v1[8..12].copy_from_slice(&1u32.to_le_bytes());
        let mut h = Fnv1a::default();
        h.update(&v1);
        v1.extend_from_slice(&h.0.to_le_bytes());
        assert_eq!(read_checkpoint(&v1).unwrap().pixels, pixels);
        // A target below a pixel's sample count (with a valid checksum) is refused.
        let mut low = with_targets[..with_targets.len() - 8].to_vec();
        let at = low.len() - 8 * 6;
        low[at..at + 8].copy_from_slice(&0u64.to_le_bytes());
        let mut h = Fnv1a::default();
        h.update(&low);
        low.extend_from_slice(&h.0.to_le_bytes());
        assert!(read_checkpoint(&low)
            .unwrap_err()
            .contains("below its sample count"));
        for bytes in [&with_targets, &bytes] {
            for len in 0..bytes.len() {
                assert!(
                    read_checkpoint(&bytes[..len]).is_err(),
                    "truncated to {len}"
                );
            }
            for i in 0..bytes.len() {
                for bit in [0x01u8, 0x80] {
                    let mut b = bytes.clone();
                    b[i] ^= bit;
                    assert!(
                        read_checkpoint(&b).is_err(),
                        "byte {i} bit {bit:#x} flipped"
                    );
                }
            }
        }
        // A huge size in the header with a matching checksum: rejected by length, no allocation.
        let mut b = bytes.clone();
        b[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        b[16..20].copy_from_slice(&u32::MAX.to_le_bytes());
        let end = b.len() - 8;
        let mut h = Fnv1a::default();
        h.update(&b[..end]);
        b[end..].copy_from_slice(&h.0.to_le_bytes());
        assert!(read_checkpoint(&b).unwrap_err().contains("truncated"));
    }
}

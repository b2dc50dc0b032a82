//! Decoded texture images shared among the textures that read them: a texture declared once and
//! referenced from several BSDFs, or one file named by several textures with the same decoding,
//! holds one copy of its pixels instead of one per use (a real scene reuses its textures often;
//! `tessera info` counts the distinct copies).
//!
//! The cache holds weak references, so it keeps no image alive on its own. An entry is keyed by
//! the file's canonical path, length and modification time and by the decoding settings, so a
//! file edited between two loads in one process is read again. Sharing changes no value: the
//! pixels are those the file decodes to.
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Weak};
use std::time::SystemTime;
use tessera_core::glam::Vec3;

/// What a decoded image depends on.
#[derive(Clone, PartialEq, Eq, Hash)]
struct Key {
    path: PathBuf,
    len: u64,
    modified: Option<SystemTime>,
    raw: bool,
    unit: bool,
    scale: [u32; 3],
}

/// A decoded image: width, height and pixels.
type Decoded = (usize, usize, Arc<[Vec3]>);

/// A remembered image: width, height and its pixels while some texture holds them.
type Entry = (usize, usize, Weak<[Vec3]>);

thread_local! {
    static CACHE: RefCell<HashMap<Key, Entry>> = RefCell::new(HashMap::new());
}

/// The pixels of `path` decoded with `raw`, `unit` and `scale`: shared with a texture that
/// already holds them, else made by `decode` (and remembered).
pub(crate) fn shared_pixels(
    path: &Path,
    raw: bool,
    unit: bool,
    scale: Vec3,
    decode: impl FnOnce() -> Result<Decoded, String>,
) -> Result<Decoded, String> {
    let key = std::fs::canonicalize(path).ok().and_then(|path| {
        let meta = std::fs::metadata(&path).ok()?;
        Some(Key {
            path,
            len: meta.len(),
            modified: meta.modified().ok(),
            raw,
            unit,
            scale: scale.to_array().map(f32::to_bits),
        })
    });
    let Some(key) = key else {
        return decode();
    };
    let held = CACHE.with(|c| {
        let c = c.borrow();
        let (w, h, weak) = c.get(&key)?;
        Some((*w, *h, weak.upgrade()?))
    });
    if let Some(d) = held {
        return Ok(d);
    }
    let (w, h, pixels) = decode()?;
    CACHE.with(|c| {
        let mut c = c.borrow_mut();
        c.retain(|_, (_, _, weak)| weak.strong_count() > 0);
        c.insert(key, (w, h, Arc::downgrade(&pixels)));
    });
    Ok((w, h, pixels))
}

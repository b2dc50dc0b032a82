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
use tessera_core::texture::{CodeTable, Texels};

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
type Decoded = (usize, usize, Texels);

/// A remembered image: width, height and its pixels while some texture holds them.
type Entry = (usize, usize, Held);

/// [`Texels`] held weakly.
enum Held {
    Float(Weak<[Vec3]>),
    Codes(Weak<[[u8; 3]]>, Weak<CodeTable>),
}

impl Held {
    fn of(t: &Texels) -> Held {
        match t {
            Texels::Float(p) => Held::Float(Arc::downgrade(p)),
            Texels::Codes(c, t) => Held::Codes(Arc::downgrade(c), Arc::downgrade(t)),
        }
    }

    fn upgrade(&self) -> Option<Texels> {
        Some(match self {
            Held::Float(p) => Texels::Float(p.upgrade()?),
            Held::Codes(c, t) => Texels::Codes(c.upgrade()?, t.upgrade()?),
        })
    }

    fn alive(&self) -> bool {
        match self {
            Held::Float(p) => p.strong_count() > 0,
            Held::Codes(c, _) => c.strong_count() > 0,
        }
    }
}

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
        c.retain(|_, (_, _, held)| held.alive());
        c.insert(key, (w, h, Held::of(&pixels)));
    });
    Ok((w, h, pixels))
}

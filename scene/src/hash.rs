//! The hash that identifies a scene: checkpoints and part files record it, so a resume or a
//! merge refuses parts of another scene. The loader computes it from the bytes it parses, so the
//! file is read once.

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

/// A scene hash with a dialect chosen on the command line mixed in (a dialect the file declares
/// is already in its bytes): the same file rendered with other conventions is another image.
pub(crate) fn with_dialect(hash: u64, dialect: crate::xml::Dialect) -> u64 {
    let mut h = Fnv1a(hash);
    h.update(b"dialect=");
    h.update(dialect.name().as_bytes());
    h.0
}

//! The scene hash recorded in part files: parts made from different scene files or different
//! `-D` overrides are refused by `tessera merge`.
use std::path::Path;

/// 64-bit FNV-1a, fed incrementally.
struct Fnv(u64);

impl Fnv {
    fn feed(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    /// A length-prefixed field, so ("ab", "c") and ("a", "bc") hash differently.
    fn field(&mut self, bytes: &[u8]) {
        self.feed(&(bytes.len() as u64).to_le_bytes());
        self.feed(bytes);
    }
}

/// A hash of a scene's top-level file bytes and its `-D name=value` overrides (in the order
/// given). Files the scene includes or references (meshes, textures) are not hashed.
pub fn scene_hash(path: &Path, defines: &[(String, String)]) -> Result<u64, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(scene_hash_bytes(&bytes, defines))
}

/// [`scene_hash`] of scene text already in memory.
pub fn scene_hash_bytes(bytes: &[u8], defines: &[(String, String)]) -> u64 {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    h.field(bytes);
    for (k, v) in defines {
        h.field(k.as_bytes());
        h.field(v.as_bytes());
    }
    h.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defines_and_bytes_change_the_hash() {
        let d = |k: &str, v: &str| vec![(k.to_string(), v.to_string())];
        let a = scene_hash_bytes(b"<scene/>", &[]);
        assert_eq!(a, scene_hash_bytes(b"<scene/>", &[]));
        assert_ne!(a, scene_hash_bytes(b"<scene />", &[]));
        assert_ne!(a, scene_hash_bytes(b"<scene/>", &d("spp", "4")));
        assert_ne!(
            scene_hash_bytes(b"x", &d("ab", "c")),
            scene_hash_bytes(b"x", &d("a", "bc"))
        );
    }
}

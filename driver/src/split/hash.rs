//! The scene hash recorded in part files: parts made from different scene files or different
//! `-D` overrides are refused by `tessera merge`. It is the checkpoint's hash
//! ([`crate::checkpoint::scene_hash`]: FNV-1a 64 over the top-level file's bytes and the defines),
//! so a part and a checkpoint of the same render name the scene alike.
use std::path::Path;

/// The hash of a scene file and its `-D name=value` overrides. Files the scene includes or
/// references (meshes, textures) are not hashed.
pub fn scene_hash(path: &Path, defines: &[(String, String)]) -> Result<u64, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(crate::checkpoint::scene_hash(&bytes, defines))
}

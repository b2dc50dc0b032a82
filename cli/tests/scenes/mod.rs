//! Loading the repository's scenes in driver tests (shared by several test files).

use std::path::{Path, PathBuf};
use tessera_scene::{load_scene, LoadedScene};

/// `scenes/NAME` of the repository.
pub fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
}

/// Loads `scenes/NAME` with `-D` style overrides; panics with the error otherwise.
pub fn load(name: &str, defines: &[(&str, &str)]) -> LoadedScene {
    let defines: Vec<(String, String)> = defines
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    load_scene(&scene_path(name), &defines).unwrap_or_else(|e| panic!("{name}: {e}"))
}

//! Scene loading: a scene file (Mitsuba 3 or Nori dialect) to a core [`Scene`] plus the render
//! settings the file carries (integrator, sample count, seed).
mod bsdfs;
mod build;
mod emitters;
mod integrator;
mod sensor;
mod shapes;
mod util;

pub use integrator::integrator_from_name;

use crate::error::InputError;
use std::path::Path;
use tessera_core::integrator::Integrator;
use tessera_core::scene::Scene;

/// A loaded scene with the settings its file asks for.
#[derive(Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// The integrator the file names (default `path`).
    pub integrator: Integrator,
    /// Samples per pixel from the sampler (default 4, as in Mitsuba 3).
    pub spp: u64,
    /// Seed from the sampler (default 0).
    pub seed: u64,
    /// Things that load but are not rendered exactly as written (one line each).
    pub warnings: Vec<String>,
}

/// Loads a scene file; `defines` are `-D name=value` overrides of `<default>`s.
pub fn load_scene(path: &Path, defines: &[(String, String)]) -> Result<LoadedScene, InputError> {
    let root = crate::xml::load_file(path, defines)?;
    build::build(&root)
}

/// Loads a scene from text as if read from `virtual_path` (relative paths resolve beside it).
pub fn load_scene_str(
    text: &str,
    virtual_path: &Path,
    defines: &[(String, String)],
) -> Result<LoadedScene, InputError> {
    let root = crate::xml::load_str(text, virtual_path, defines)?;
    build::build(&root)
}

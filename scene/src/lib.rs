//! Tessera's scene loading: a scene file (Mitsuba 3 or Nori dialect) to a core
//! [`tessera_core::scene::Scene`] plus the render settings the file carries (integrator, sample
//! count, seed). XML parsing with located errors ([`xml`], [`error`]), meshes ([`mesh`]), images
//! ([`image`]), and one builder file per plugin family. Start from [`load_scene`].
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
pub mod error;
pub mod image;
pub mod mesh;
pub mod plugin;
pub mod reference;
pub mod xml;

mod bsdfs;
mod build;
mod emitters;
mod filter;
mod integrator;
pub(crate) mod materials;
mod sampler;
mod sensor;
mod shapes;
mod util;

pub use integrator::{integrator_names, IntegratorSpec, INTEGRATORS};
pub use sensor::{MAX_EDGE, MAX_PIXELS};

use crate::error::InputError;
use std::path::Path;
use tessera_core::integrator::Integrator;
use tessera_core::sampling::{SamplerKind, SAMPLER_NAMES};
use tessera_core::scene::Scene;

/// A loaded scene with the settings its file asks for.
#[derive(Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// The integrator the file names (default `path`).
    pub integrator: Integrator,
    /// Its name and parameters, to rebuild it with command-line changes.
    pub integrator_spec: IntegratorSpec,
    /// Samples per pixel from the sampler (default 4, as in Mitsuba 3).
    pub spp: u64,
    /// Seed from the sampler (default 0).
    pub seed: u64,
    /// Things that load but are not rendered exactly as written (one line each).
    pub warnings: Vec<String>,
}

impl LoadedScene {
    /// Switches to another sampler by name (`None`: keep the file's) and sets it up for `spp`
    /// samples per pixel (zsobol's pixel blocks depend on it; see `ZSobolSampler`).
    pub fn set_sampler(&mut self, name: Option<&str>, spp: u64) -> Result<(), String> {
        self.scene.sampler = match name {
            Some(n) => SamplerKind::from_name(n, spp)
                .ok_or_else(|| format!("unknown sampler \"{n}\" (known: {SAMPLER_NAMES})"))?,
            None => self.scene.sampler.for_spp(spp),
        };
        Ok(())
    }

    /// Switches to another integrator by name (keeping the file's parameters that apply; a name
    /// ending in `+reuse` turns on path reuse, any other name turns it off) and/or another
    /// `max_depth` (-1 = unbounded).
    pub fn set_integrator(
        &mut self,
        name: Option<&str>,
        max_depth: Option<i64>,
    ) -> Result<(), String> {
        let mut spec = self.integrator_spec.clone();
        if let Some(n) = name {
            // `NAME+reuse`: the path tracer NAME with path reuse; a name given without it
            // turns reuse off, whatever the file said.
            let (base, reuse) = match n.strip_suffix("+reuse") {
                Some(base) => (base, true),
                None => (n, false),
            };
            if reuse && !base.starts_with("path") {
                return Err(format!(
                    "\"+reuse\" needs a path tracer (path, path_mis, ...), found \"{base}\""
                ));
            }
            spec.name = base.to_string();
            spec.reuse = reuse;
        }
        if let Some(d) = max_depth {
            if d < -1 || d > u32::MAX as i64 {
                return Err(format!("max depth must be -1 or at least 0, found {d}"));
            }
            spec.max_depth = (d >= 0).then_some(d as u32);
        }
        self.integrator = spec.build().ok_or_else(|| {
            format!(
                "unknown integrator \"{}\" (known: {})",
                spec.name,
                integrator_names()
            )
        })?;
        self.integrator_spec = spec;
        Ok(())
    }
}

/// Loads a scene file; `defines` are `-D name=value` overrides of `<default>`s.
pub fn load_scene(path: &Path, defines: &[(String, String)]) -> Result<LoadedScene, InputError> {
    let root = crate::xml::load_file(path, defines)?;
    build::build(&root)
}

/// Builds a scene from an already parsed `<scene>` object (e.g. one nested in a test file).
pub fn build_scene_object(obj: &crate::xml::Object) -> Result<LoadedScene, InputError> {
    build::build(obj)
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

/// Builds a standalone BSDF from a parsed `<bsdf>` object (e.g. one inside a `chi2test`).
pub fn build_bsdf_object(obj: &crate::xml::Object) -> Result<tessera_core::bsdf::Bsdf, InputError> {
    materials::build_bsdf(obj)
}

/// Loads the first top-level `<bsdf>` of a scene file (other children are ignored), for tests
/// and tools that study one material. Relative paths (bitmaps) resolve beside the file.
pub fn load_bsdf_file(path: &Path) -> Result<tessera_core::bsdf::Bsdf, InputError> {
    let root = crate::xml::load_file(path, &[])?;
    let child = root
        .children_of(crate::xml::Kind::Bsdf)
        .next()
        .ok_or_else(|| root.error("the file has no top-level <bsdf>"))?;
    materials::build_bsdf(&child.obj)
}

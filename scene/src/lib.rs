//! Tessera's scene loading: a scene file (Mitsuba 3 or Nori dialect) to a core
//! [`tessera_core::scene::Scene`] plus the render settings the file carries (integrator, sample
//! count, seed). XML parsing with located errors ([`xml`], [`error`]), meshes ([`mesh`]), images
//! ([`image`]), and one builder file per plugin family. Start from [`load_scene`].
//!
//! # Example
//!
//! ```
//! use std::path::Path;
//! let xml = r#"<scene version="3.0.0">
//!     <sensor type="perspective">
//!         <float name="fov" value="45"/>
//!         <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="24"/></film>
//!     </sensor>
//!     <shape type="sphere"><bsdf type="diffuse"/></shape>
//!     <emitter type="constant"/>
//! </scene>"#;
//! let loaded = tessera_scene::load_scene_str(xml, Path::new("inline.xml"), &[]).unwrap();
//! let camera = &loaded.scene.camera;
//! assert_eq!((camera.width, camera.height), (32, 24));
//! assert_eq!(loaded.names.shapes, ["sphere"]);
//!
//! // A misspelt parameter is a one-line error at its line and column.
//! let typo = xml.replace("name=\"fov\"", "name=\"fvo\"");
//! let err = tessera_scene::load_scene_str(&typo, Path::new("inline.xml"), &[]).unwrap_err();
//! assert!(err.to_string().starts_with("inline.xml:3:"), "{err}");
//! ```
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]
pub mod error;
pub mod hash;
pub mod image;
pub mod mesh;
pub mod plugin;
pub mod reference;
pub mod xml;

mod bsdfs;
mod build;
mod emitters;
mod families;
mod filter;
mod integrator;
mod loaded;
pub(crate) mod materials;
mod media;
mod mitsuba_names;
mod sampler;
mod sensor;
mod shape_numbering;
mod shapes;
mod threads;
mod util;

pub use integrator::{IntegratorSpec, INTEGRATORS};
pub use integrator::{Layer, LayerSource};
pub use loaded::{LoadedScene, PluginNames};
pub use sensor::{MAX_EDGE, MAX_PIXELS};

use crate::error::InputError;
pub use crate::xml::Dialect;
use std::path::Path;

/// Loads a scene file (read once: its hash comes from the same bytes); `defines` are
/// `-D name=value` overrides of `<default>`s.
pub fn load_scene(path: &Path, defines: &[(String, String)]) -> Result<LoadedScene, InputError> {
    load_scene_as(path, defines, None)
}

/// [`load_scene`] rendered with `dialect`'s conventions whatever the file declares (`None`:
/// the file's; see [`Dialect`]). A dialect given here is part of the scene's hash.
pub fn load_scene_as(
    path: &Path,
    defines: &[(String, String)],
    dialect: Option<Dialect>,
) -> Result<LoadedScene, InputError> {
    let text = crate::xml::read_file(path)?;
    let root = crate::xml::load_str_as(&text, path, defines, dialect)?;
    let mut loaded = build::build(&root)?;
    loaded.source_hash = hash::scene_hash(text.as_bytes(), defines);
    if let Some(d) = dialect {
        loaded.source_hash = hash::with_dialect(loaded.source_hash, d);
    }
    Ok(loaded)
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
    let mut loaded = build::build(&root)?;
    loaded.source_hash = hash::scene_hash(text.as_bytes(), defines);
    Ok(loaded)
}

/// The declaration (name, parameters with their types, defaults and ranges) of the plugin
/// `name` of the family whose element is `<tag>` (`"bsdf"`, `"integrator"`, `"sampler"`, ...),
/// for tools that edit scene files and must check values the way the loader will.
pub fn plugin_declaration(tag: &str, name: &str) -> Option<plugin::Declared> {
    families::families()
        .into_iter()
        .find(|f| f.kind.tag() == tag)?
        .plugins
        .into_iter()
        .find(|p| p.is(name))
}

/// The plugin names of the family whose element is `<tag>`, in table order (aliases left out).
pub fn plugin_names(tag: &str) -> Vec<&'static str> {
    families::families()
        .into_iter()
        .find(|f| f.kind.tag() == tag)
        .map(|f| f.plugins.iter().map(|p| p.name).collect())
        .unwrap_or_default()
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

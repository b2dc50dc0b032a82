//! The shape of a texture plugin's entry, apart from the table of them (`texture.rs`), so
//! that plugins in their own files do not import the table that lists them.
use super::super::util::Result;
use crate::plugin::Plugin;
use crate::xml::Object;
use tessera_core::texture::Texture;

/// A texture plugin: built for a parameter whose values must lie in [0, 1] (`unit`) or only
/// be non-negative.
pub(crate) type TexturePlugin = Plugin<fn(&Object, bool) -> Result<Texture>>;

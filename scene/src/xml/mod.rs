//! The XML layer of the scene loader: Mitsuba 3 and Nori/Wakame scene files to a generic,
//! normalized, located object tree ([`Object`]).
//!
//! This layer knows the file syntax only: properties, objects, `<default>`/`$name`
//! parameters, `<ref>`, `<alias>`, `<include>`, `<path>`, transforms, and the Nori dialect (mapped onto
//! Mitsuba 3 vocabulary). What the objects mean is the scene builder's business; it reads the
//! tree through the typed getters of [`Object`] and finally calls [`Object::check_unused`].

mod attrs;
mod building;
mod cie;
mod conventions;
mod dialect;
mod draft;
mod getters;
mod include;
mod object;
mod params;
mod parse;
mod path;
mod property;
mod recentre;
mod refs;
mod search;
pub(crate) mod source;
pub(crate) mod spectrum;
mod subst;
mod transform;
mod upgrade;
mod values;

#[cfg(test)]
mod tests;

use std::path::Path;

pub use conventions::Dialect;
pub use dialect::snake_case;
pub use object::{Child, Kind, Object, Prop, Value};
pub use parse::{MAX_DEPTH, MAX_INCLUDE_DEPTH};
pub use recentre::RECENTRE_FROM;
pub use source::MAX_FILE_BYTES;

use crate::error::InputError;

/// Loads the scene file at `path` (root element `<scene>`).
///
/// `defines` are the command line's `-D name=value` pairs; they override `<default>`s.
/// Included files are looked up beside the including file, then as Mitsuba's file resolver
/// does (the main file's folder and `<path>` folders).
pub fn load_file(path: &Path, defines: &[(String, String)]) -> Result<Object, InputError> {
    parse::Parser::new(defines).load_text(&read_file(path)?, path)
}

/// Reads a scene file's text (checked: a regular file, at most 64 MiB, UTF-8).
pub(crate) fn read_file(path: &Path) -> Result<String, InputError> {
    source::read_text(path).map_err(|m| InputError::file(path, m))
}

/// Loads a scene from text, as if it were read from `virtual_path` (used in locations;
/// includes resolve relative to its directory).
pub fn load_str(
    text: &str,
    virtual_path: &Path,
    defines: &[(String, String)],
) -> Result<Object, InputError> {
    load_str_as(text, virtual_path, defines, None)
}

/// [`load_str`] with the conventions of `dialect` whatever the text declares (`None`: the
/// text's, see [`Dialect`]).
pub(crate) fn load_str_as(
    text: &str,
    virtual_path: &Path,
    defines: &[(String, String)],
    dialect: Option<Dialect>,
) -> Result<Object, InputError> {
    parse::Parser::new(defines)
        .with_dialect(dialect)
        .load_text(text, virtual_path)
}

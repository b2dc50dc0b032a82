//! `<path value="folder"/>`: a folder where relative file names are also looked up.
//!
//! As in Mitsuba: only at the top level of a scene; a relative folder is taken beside the file
//! that declares it, or else wherever the file resolver finds it; the folder goes first on the
//! resolver's list (see `search.rs`).

use std::path::Path;

use roxmltree::Node;

use super::attrs::Attrs;
use super::building::Building;
use super::object::Kind;
use super::parse::{no_content, Parser, Result};
use super::search::lookup;
use super::source::Source;

impl Parser {
    /// Reads a `<path>` element into the resolver.
    pub(super) fn parse_path(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        attrs: &Attrs,
        b: &Building,
    ) -> Result<()> {
        no_content(src, node)?;
        attrs.allow(&["value"])?;
        if b.kind != Kind::Scene {
            return Err(attrs.error(format!(
                "<path> is only allowed at the top level of a scene, not inside {}",
                b.describe()
            )));
        }
        let value = attrs.require("value")?;
        if value.value.is_empty() {
            return Err(value.error(&attrs.tag, "must not be empty"));
        }
        let name = Path::new(&value.value);
        let beside = src.dir.join(name);
        let folder = if name.is_absolute() || beside.exists() {
            beside
        } else {
            lookup(&self.resolver, name).unwrap_or(beside)
        };
        if !folder.is_dir() {
            return Err(value.error(
                &attrs.tag,
                &format!("folder \"{}\" not found", folder.display()),
            ));
        }
        self.resolver.insert(0, folder);
        Ok(())
    }
}

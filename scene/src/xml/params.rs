//! `$name` parameters: `<default>` declarations, mentions, and the check of `-D` defines.

use std::path::Path;

use roxmltree::Node;

use super::attrs::Attrs;
use super::parse::{no_content, Parser, Result};
use super::source::Source;
use super::subst::is_valid_name;
use crate::error::InputError;

impl Parser {
    /// Reads a `<default>` element: sets the parameter unless a `-D` (or an earlier
    /// `<default>`) already did.
    pub(super) fn parse_default(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        attrs: &Attrs,
    ) -> Result<()> {
        no_content(src, node)?;
        attrs.allow(&["name", "value"])?;
        let name = attrs.require("name")?;
        let value = attrs.require("value")?;
        if !is_valid_name(&name.value) {
            return Err(name.error(
                &attrs.tag,
                &format!(
                    "\"{}\" is not a valid parameter name (use letters, digits, _)",
                    name.value
                ),
            ));
        }
        self.params
            .entry(name.value.clone())
            .or_insert_with(|| value.value.clone());
        self.known_params.insert(name.value.clone());
        Ok(())
    }

    /// Records every `$name` a file's text mentions.
    pub(super) fn note_mentions(&mut self, text: &str) {
        let mut rest = text;
        while let Some(i) = rest.find('$') {
            rest = &rest[i + 1..];
            let n = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            if n > 0 {
                self.known_params.insert(rest[..n].to_string());
            }
        }
    }

    /// Fails on a `-D` define that no file declares (`<default>`) or uses (`$name`).
    pub(super) fn check_defines(&self, path: &Path) -> Result<()> {
        // A -D that no file declares or uses is almost always a typo: say so.
        if let Some(d) = self
            .define_names
            .iter()
            .find(|d| !self.known_params.contains(*d))
        {
            return Err(InputError::file(
                path,
                format!("-D {d}: the scene has no <default name=\"{d}\"> and never uses ${d}"),
            ));
        }
        Ok(())
    }
}

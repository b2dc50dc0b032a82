//! `<include>`: another file's content spliced in place, with depth and cycle checks.
//!
//! The file name is looked up as Mitsuba does: beside the including file first, then in the
//! resolver's folders (the main file's folder, `<path>` folders; see `search.rs`).

use std::sync::Arc;

use roxmltree::Node;

use super::attrs::Attrs;
use super::building::Building;
use super::parse::{
    check_version, file_version, no_content, strip_bom, Parser, Result, MAX_INCLUDE_DEPTH,
};
use super::search::lookup;
use super::source::{canonical, parse_document, read_text, Source};

impl Parser {
    /// Reads an `<include>` element: the included file's root element (or, for a `<scene>`,
    /// its content) goes into `b`.
    pub(super) fn parse_include(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        attrs: &Attrs,
        b: &mut Building,
        depth: usize,
    ) -> Result<()> {
        no_content(src, node)?;
        attrs.allow(&["filename"])?;
        let fname = attrs.require("filename")?;
        if fname.value.is_empty() {
            return Err(fname.error(&attrs.tag, "must not be empty"));
        }
        // The included file reads with the including file's folder in front, and any
        // `<path>` it declares ends with it.
        let saved = self.resolver.clone();
        self.resolver.insert(0, src.dir.clone());
        let result = self.include_file(attrs, &fname.value, b, depth);
        self.resolver = saved;
        result
    }

    /// Finds, checks and reads the included file.
    fn include_file(
        &mut self,
        attrs: &Attrs,
        fname: &str,
        b: &mut Building,
        depth: usize,
    ) -> Result<()> {
        let path = lookup(&self.resolver, std::path::Path::new(fname))
            .unwrap_or_else(|| self.resolver[0].join(fname));
        if self.files.len() >= MAX_INCLUDE_DEPTH {
            return Err(attrs.error(format!(
                "includes are nested deeper than {MAX_INCLUDE_DEPTH} levels"
            )));
        }
        let key = canonical(&path);
        if self.files.contains(&key) {
            return Err(attrs.error(format!(
                "include cycle: \"{}\" is already being read (it includes itself, directly or not)",
                path.display()
            )));
        }
        let text = read_text(&path)
            .map_err(|m| attrs.error(format!("cannot include \"{}\": {m}", path.display())))?;
        let text = strip_bom(&text);
        self.note_mentions(text);
        let file = Arc::new(path);
        let doc = parse_document(text, &file)?;
        let isrc = Source::new(file, text);
        let root = doc.root_element();
        self.files.push(key);
        self.versions.push(None);
        let result = if root.tag_name().name() == "scene" {
            // The included scene's content is spliced in place of the <include>.
            Attrs::read(root, &isrc, &self.params)
                .and_then(|ra| {
                    ra.allow(&["version"])?;
                    check_version(&ra)?;
                    *self.versions.last_mut().expect("pushed above") = file_version(&ra);
                    Ok(())
                })
                .and_then(|()| self.parse_body(&isrc, root, b, depth + 1))
        } else {
            self.parse_item(&isrc, root, b, depth + 1)
        };
        self.files.pop();
        self.versions.pop();
        result
    }
}

//! The element walker: XML elements to [`Object`]s, with `<default>`, `<ref>`, `<alias>` and
//! `<include>` resolved and the Nori dialect normalized.
//!
//! State shared across a whole load (including included files): the parameter table for
//! `$name` substitution, the table of object ids, and the stack of files being included.
//! Recursion is bounded: elements may nest at most [`MAX_DEPTH`] levels (counting through
//! includes) and includes at most [`MAX_INCLUDE_DEPTH`] levels.
//!
//! This file holds the walk itself; the elements other than objects are read in
//! `property.rs`, `refs.rs` (`<ref>`, `<alias>`), `params.rs` (`<default>`) and `include.rs`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

use roxmltree::Node;

use super::attrs::Attrs;
use super::building::Building;
use super::conventions::{read_instruction, Dialect};
use super::dialect::element_alias;
use super::draft::{finalize, Draft, DraftChild, Target};
use super::object::{Kind, Object};
use super::recentre::recentre;
use super::search::folder_of;
use super::source::canonical;
use super::source::{check_size, parse_document, Source};
use super::transform;
use super::upgrade::{needs_upgrade, parse_version, upgrade, Version};
use crate::error::{InputError, Loc};

pub(super) type Result<T> = std::result::Result<T, InputError>;

/// Deepest element nesting accepted (the root `<scene>` is level 1).
pub const MAX_DEPTH: usize = 64;

/// Deepest `<include>` nesting accepted.
pub const MAX_INCLUDE_DEPTH: usize = 32;

/// Mitsuba elements this renderer does not implement (a clearer error than "unknown").
const UNSUPPORTED: &[&str] = &["tensor"];

/// Property element names (after dialect aliasing).
const PROPERTY_TAGS: &[&str] = &[
    "float",
    "integer",
    "boolean",
    "string",
    "rgb",
    "spectrum",
    "point",
    "vector",
    "transform",
];

/// What an element is.
enum Item<'a> {
    Object(Kind),
    Property(&'a str),
    Ref,
    Include,
    Default,
    Alias,
    Path,
}

/// The state of one load.
pub struct Parser {
    /// `$name` parameters: `-D` defines first, then `<default>`s that were not yet set.
    pub(super) params: HashMap<String, String>,
    /// Names of the `-D` defines, which the scene must declare or use.
    pub(super) define_names: Vec<String>,
    /// Parameter names the files declare (`<default>`) or mention (`$name`).
    pub(super) known_params: std::collections::HashSet<String>,
    /// Objects declared with an `id` (or aliased): their index in `drafts`, and where.
    pub(super) ids: HashMap<String, (usize, Loc)>,
    /// Every object read so far (taken out when the tree is finalized).
    pub(super) drafts: Vec<Option<Draft>>,
    /// Mitsuba's file resolver as it is now: the folders relative names resolve in, first
    /// to last (see `search.rs`).
    pub(super) resolver: Vec<PathBuf>,
    /// Ids of objects whose element is still being read.
    pub(super) open_ids: HashMap<String, Loc>,
    /// Files being read, outermost first (canonical paths when they exist).
    pub(super) files: Vec<PathBuf>,
    /// Located warnings about the files (handed to the root object).
    pub(super) warnings: Vec<String>,
    /// The version attribute of each file in `files` (`None`: none, as in Nori files).
    pub(super) versions: Vec<Option<Version>>,
    /// The command line's `--dialect`, which overrides the file's.
    pub(super) dialect: Option<Dialect>,
}

pub(super) fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// Validates a `version="3.0.0"` attribute (one to three dot-separated numbers).
pub(super) fn check_version(a: &Attrs) -> Result<()> {
    if let Some(v) = a.get("version") {
        let parts: Vec<&str> = v.value.split('.').collect();
        let ok = parts.len() <= 3
            && parts
                .iter()
                .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()));
        if !ok {
            return Err(v.error(
                &a.tag,
                &format!("invalid version \"{}\" (expected e.g. \"3.0.0\")", v.value),
            ));
        }
    }
    Ok(())
}

/// The version a root element declares (checked by [`check_version`] first).
pub(super) fn file_version(a: &Attrs) -> Option<Version> {
    a.get("version").and_then(|v| parse_version(&v.value))
}

/// Fails when a non-object element contains elements or text.
pub(super) fn no_content(src: &Source<'_>, node: Node<'_, '_>) -> Result<()> {
    for ch in node.children() {
        if ch.is_element() {
            return Err(InputError::at(
                &src.loc(ch.range().start),
                format!(
                    "<{}> cannot contain elements (found <{}>)",
                    node.tag_name().name(),
                    ch.tag_name().name()
                ),
            ));
        }
        check_text(src, node, ch)?;
    }
    Ok(())
}

/// Fails when `ch` is a text node with something other than whitespace.
pub(super) fn check_text(src: &Source<'_>, parent: Node<'_, '_>, ch: Node<'_, '_>) -> Result<()> {
    if !ch.is_text() {
        return Ok(());
    }
    let text = ch.text().unwrap_or("");
    if text.trim().is_empty() {
        return Ok(());
    }
    let range = ch.range();
    let raw = &src.text()[range.clone()];
    let lead = raw.len() - raw.trim_start().len();
    let shown: String = text.trim().chars().take(40).collect();
    let more = if text.trim().chars().count() > 40 {
        "..."
    } else {
        ""
    };
    Err(InputError::at(
        &src.loc(range.start + lead),
        format!(
            "unexpected text \"{shown}{more}\" inside <{}>",
            parent.tag_name().name()
        ),
    ))
}

impl Parser {
    /// A parser with the given `-D name=value` defines.
    pub fn new(defines: &[(String, String)]) -> Self {
        Parser {
            params: defines.iter().cloned().collect(),
            define_names: defines.iter().map(|(k, _)| k.clone()).collect(),
            known_params: std::collections::HashSet::new(),
            ids: HashMap::new(),
            drafts: Vec::new(),
            resolver: Vec::new(),
            open_ids: HashMap::new(),
            files: Vec::new(),
            versions: Vec::new(),
            warnings: Vec::new(),
            dialect: None,
        }
    }

    /// Renders the file with `dialect`'s conventions whatever the file says.
    pub(crate) fn with_dialect(mut self, dialect: Option<Dialect>) -> Self {
        self.dialect = dialect;
        self
    }

    /// Parses a whole scene file's text; `path` names it in locations and resolves includes.
    pub(crate) fn load_text(&mut self, text: &str, path: &Path) -> Result<Object> {
        check_size(text).map_err(|m| InputError::file(path, m))?;
        let text = strip_bom(text);
        let file = Arc::new(path.to_path_buf());
        let doc = parse_document(text, &file)?;
        let src = Source::new(file, text);
        let declared = read_instruction(&doc, |at| src.loc(at))?;
        let root = doc.root_element();
        let loc = src.loc(root.range().start);
        // A scene file, or a Nori test file (`<test type="ttest|chi2test">` holding scenes).
        let root_kind = match root.tag_name().name() {
            "scene" => Kind::Scene,
            "test" => Kind::Test,
            other => {
                return Err(InputError::at(
                    &loc,
                    format!("the root element must be <scene> (or <test>), found <{other}>"),
                ))
            }
        };
        self.note_mentions(text);
        let attrs = Attrs::read(root, &src, &self.params)?;
        self.files.push(canonical(path));
        self.versions.push(file_version(&attrs));
        self.resolver = vec![folder_of(path)];
        let draft = self.build_object(&src, root, root_kind, &attrs, None, 1)?;
        self.files.pop();
        self.versions.pop();
        self.check_defines(path)?;
        let root = self.drafts.len();
        self.drafts.push(Some(draft));
        let search: Rc<[PathBuf]> = std::mem::take(&mut self.resolver).into();
        let shift = recentre(&mut self.drafts);
        let mut obj = finalize(&mut self.drafts, &self.ids, root, &search)?;
        obj.frame_origin = shift.unwrap_or_default();
        obj.dialect = self.dialect.or(declared).unwrap_or_default();
        obj.load_warnings = std::mem::take(&mut self.warnings);
        Ok(obj)
    }

    /// Reads an object element into a [`Draft`] (registering nothing).
    pub(super) fn build_object(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        kind: Kind,
        attrs: &Attrs,
        parent: Option<&Building>,
        depth: usize,
    ) -> Result<Draft> {
        let (plugin, id, name) = if kind == Kind::Scene {
            attrs.allow(&["version"])?;
            check_version(attrs)?;
            (String::new(), None, None)
        } else {
            attrs.allow(&["type", "id", "name"])?;
            let ty = attrs.require("type")?;
            if ty.value.trim().is_empty() {
                return Err(ty.error(&attrs.tag, "must not be empty"));
            }
            let id = match attrs.get("id") {
                Some(a) => {
                    if a.value.is_empty() {
                        return Err(a.error(&attrs.tag, "must not be empty"));
                    }
                    self.check_new_id(&a.value, &a.loc)?;
                    Some(a.value.clone())
                }
                None => None,
            };
            let name = match attrs.get("name") {
                Some(a) if a.value.is_empty() => {
                    return Err(a.error(&attrs.tag, "must not be empty"))
                }
                Some(a) => Some(match parent {
                    Some(p) => p.param_name(&a.value),
                    None => a.value.clone(),
                }),
                None => None,
            };
            (ty.value.trim().to_string(), id, name)
        };
        if let Some(id) = &id {
            self.open_ids.insert(id.clone(), attrs.loc.clone());
        }
        let mut b = Building::new(kind, plugin);
        let body = self.parse_body(src, node, &mut b, depth);
        if let Some(id) = &id {
            self.open_ids.remove(id);
        }
        body?;
        if needs_upgrade(self.versions.last().copied().flatten()) {
            upgrade(&mut b)?;
        }
        Ok(Draft {
            kind,
            plugin: b.plugin,
            id,
            name,
            loc: attrs.loc.clone(),
            props: b.props,
            children: b.children,
        })
    }

    /// Reads the content of an object element into `b`.
    pub(super) fn parse_body(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        b: &mut Building,
        depth: usize,
    ) -> Result<()> {
        for ch in node.children() {
            if ch.is_element() {
                self.parse_item(src, ch, b, depth + 1)?;
            } else {
                check_text(src, node, ch)?;
            }
        }
        Ok(())
    }

    /// What an element is, or a located error for unknown elements.
    fn classify<'t>(&self, src: &Source<'_>, node: Node<'_, 't>, b: &Building) -> Result<Item<'t>> {
        let written = node.tag_name().name();
        let tag = element_alias(written);
        let err = |msg: String| Err(InputError::at(&src.loc(node.range().start), msg));
        if let Some(kind) = Kind::from_tag(tag) {
            if kind == Kind::Scene && b.kind != Kind::Test {
                return err(
                    "<scene> is only allowed as the root element (or inside a Nori <test>)".into(),
                );
            }
            return Ok(Item::Object(kind));
        }
        match tag {
            "ref" => Ok(Item::Ref),
            "include" => Ok(Item::Include),
            "default" => Ok(Item::Default),
            "alias" => Ok(Item::Alias),
            "path" => Ok(Item::Path),
            t if PROPERTY_TAGS.contains(&t) => Ok(Item::Property(tag)),
            t if transform::is_op(t) => {
                err(format!("<{written}> is only allowed inside <transform>"))
            }
            t if UNSUPPORTED.contains(&t) => {
                // Name the plugin too.
                let plugin = match node.attribute("type") {
                    Some(ty) => format!(" type=\"{ty}\""),
                    None => String::new(),
                };
                err(format!(
                    "unsupported element <{written}{plugin}> (not implemented by this renderer)"
                ))
            }
            _ => err(format!("unknown element <{written}>")),
        }
    }

    /// Reads one element inside an object into `b`.
    pub(super) fn parse_item(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        b: &mut Building,
        depth: usize,
    ) -> Result<()> {
        if depth > MAX_DEPTH {
            return Err(InputError::at(
                &src.loc(node.range().start),
                format!("elements are nested deeper than {MAX_DEPTH} levels"),
            ));
        }
        let item = self.classify(src, node, b)?;
        let attrs = Attrs::read(node, src, &self.params)?;
        match item {
            Item::Object(kind) => {
                let draft = self.build_object(src, node, kind, &attrs, Some(b), depth)?;
                let name = draft.name.clone();
                let at = self.drafts.len();
                if let Some(id) = &draft.id {
                    self.ids.insert(id.clone(), (at, attrs.loc.clone()));
                }
                self.drafts.push(Some(draft));
                b.add_child(DraftChild {
                    name,
                    target: Target::Node(at),
                    loc: attrs.loc.clone(),
                    is_ref: false,
                })
            }
            Item::Property(tag) => {
                let prop = self.parse_property(src, node, tag, &attrs, b, depth)?;
                b.add_prop(prop)
            }
            Item::Ref => self.parse_ref(src, node, &attrs, b),
            Item::Include => self.parse_include(src, node, &attrs, b, depth),
            Item::Default => self.parse_default(src, node, &attrs),
            Item::Alias => self.parse_alias(src, node, &attrs),
            Item::Path => self.parse_path(src, node, &attrs, b),
        }
    }
}

//! The element walker: XML elements to [`Object`]s, with `<default>`, `<ref>`, `<alias>` and
//! `<include>` resolved and the Nori dialect normalized.
//!
//! State shared across a whole load (including included files): the parameter table for
//! `$name` substitution, the table of object ids, and the stack of files being included.
//! Recursion is bounded: elements may nest at most [`MAX_DEPTH`] levels (counting through
//! includes) and includes at most [`MAX_INCLUDE_DEPTH`] levels.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

use glam::DMat4;
use roxmltree::Node;

use super::attrs::Attrs;
use super::dialect::{element_alias, param_name};
use super::object::{Child, Kind, Object, Prop, Value};
use super::source::{check_size, parse_document, read_text, Source};
use super::subst::is_valid_name;
use super::transform;
use crate::error::{InputError, Loc};

type Result<T> = std::result::Result<T, InputError>;

/// Deepest element nesting accepted (the root `<scene>` is level 1).
pub const MAX_DEPTH: usize = 64;

/// Deepest `<include>` nesting accepted.
pub const MAX_INCLUDE_DEPTH: usize = 32;

/// Mitsuba elements this renderer does not implement (a clearer error than "unknown").
const UNSUPPORTED: &[&str] = &["medium", "phase", "volume", "path", "tensor"];

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
}

/// An object whose element is being read.
struct Building {
    kind: Kind,
    plugin: String,
    props: Vec<Prop>,
    children: Vec<Child>,
    /// Parameter names (properties and named children) seen so far, for duplicates.
    names: HashMap<String, Loc>,
}

impl Building {
    fn new(kind: Kind, plugin: String) -> Self {
        Building {
            kind,
            plugin,
            props: Vec::new(),
            children: Vec::new(),
            names: HashMap::new(),
        }
    }

    fn describe(&self) -> String {
        if self.plugin.is_empty() {
            self.kind.tag().to_string()
        } else {
            format!("{} \"{}\"", self.kind, self.plugin)
        }
    }

    /// Normalizes a parameter name for this object.
    fn param_name(&self, raw: &str) -> String {
        param_name(raw, self.kind, &self.plugin)
    }

    fn claim_name(&mut self, name: &str, loc: &Loc) -> Result<()> {
        if let Some(first) = self.names.get(name) {
            return Err(InputError::at(
                loc,
                format!(
                    "parameter \"{name}\" of {} is specified twice (first at {first})",
                    self.describe()
                ),
            ));
        }
        self.names.insert(name.to_string(), loc.clone());
        Ok(())
    }

    fn add_prop(&mut self, prop: Prop) -> Result<()> {
        self.claim_name(&prop.name, &prop.loc)?;
        self.props.push(prop);
        Ok(())
    }

    fn add_child(&mut self, child: Child) -> Result<()> {
        if let Some(n) = &child.name {
            self.claim_name(n, &child.loc)?;
        }
        self.children.push(child);
        Ok(())
    }
}

/// The state of one load.
pub struct Parser {
    /// `$name` parameters: `-D` defines first, then `<default>`s that were not yet set.
    params: HashMap<String, String>,
    /// Names of the `-D` defines, which the scene must declare or use.
    define_names: Vec<String>,
    /// Parameter names the files declare (`<default>`) or mention (`$name`).
    known_params: std::collections::HashSet<String>,
    /// Objects declared with an `id` (or aliased), and where.
    ids: HashMap<String, (Rc<Object>, Loc)>,
    /// Ids of objects whose element is still being read.
    open_ids: HashMap<String, Loc>,
    /// Files being read, outermost first (canonical paths when they exist).
    files: Vec<PathBuf>,
}

/// The canonical form of a path when it exists, else the path itself.
fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// Validates a `version="3.0.0"` attribute (one to three dot-separated numbers).
fn check_version(a: &Attrs) -> Result<()> {
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

/// Fails when a non-object element contains elements or text.
fn no_content(src: &Source<'_>, node: Node<'_, '_>) -> Result<()> {
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
fn check_text(src: &Source<'_>, parent: Node<'_, '_>, ch: Node<'_, '_>) -> Result<()> {
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
            open_ids: HashMap::new(),
            files: Vec::new(),
        }
    }

    /// Parses a whole scene file's text; `path` names it in locations and resolves includes.
    pub fn load_text(&mut self, text: &str, path: &Path) -> Result<Object> {
        check_size(text).map_err(|m| InputError::file(path, m))?;
        let text = strip_bom(text);
        let file = Arc::new(path.to_path_buf());
        let doc = parse_document(text, &file)?;
        let src = Source::new(file, text);
        let root = doc.root_element();
        let loc = src.loc(root.range().start);
        if root.tag_name().name() != "scene" {
            return Err(InputError::at(
                &loc,
                format!(
                    "the root element must be <scene>, found <{}>",
                    root.tag_name().name()
                ),
            ));
        }
        self.note_mentions(text);
        let attrs = Attrs::read(root, &src, &self.params)?;
        self.files.push(canonical(path));
        let obj = self.build_object(&src, root, Kind::Scene, &attrs, None, 1)?;
        self.files.pop();
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
        Ok(obj)
    }

    /// Records every `$name` a file's text mentions.
    fn note_mentions(&mut self, text: &str) {
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

    /// Reads an object element into an [`Object`] (registering nothing).
    fn build_object(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        kind: Kind,
        attrs: &Attrs,
        parent: Option<&Building>,
        depth: usize,
    ) -> Result<Object> {
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
        Ok(Object::new(
            kind,
            b.plugin,
            id,
            name,
            attrs.loc.clone(),
            b.props,
            b.children,
        ))
    }

    /// Fails when `id` is already declared (or being declared).
    fn check_new_id(&self, id: &str, loc: &Loc) -> Result<()> {
        let first = self
            .ids
            .get(id)
            .map(|(_, l)| l)
            .or_else(|| self.open_ids.get(id));
        match first {
            Some(first) => Err(InputError::at(
                loc,
                format!("duplicate id \"{id}\" (first declared at {first})"),
            )),
            None => Ok(()),
        }
    }

    /// Reads the content of an object element into `b`.
    fn parse_body(
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
            t if PROPERTY_TAGS.contains(&t) => Ok(Item::Property(tag)),
            t if transform::is_op(t) => {
                err(format!("<{written}> is only allowed inside <transform>"))
            }
            t if UNSUPPORTED.contains(&t) => err(format!(
                "unsupported element <{written}> (not implemented by this renderer)"
            )),
            _ => err(format!("unknown element <{written}>")),
        }
    }

    /// Reads one element inside an object into `b`.
    fn parse_item(
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
                let obj = self.build_object(src, node, kind, &attrs, Some(b), depth)?;
                let name = obj.name.clone();
                let obj = Rc::new(obj);
                if let Some(id) = &obj.id {
                    self.ids
                        .insert(id.clone(), (obj.clone(), attrs.loc.clone()));
                }
                b.add_child(Child::new(name, obj, attrs.loc.clone(), false))
            }
            Item::Property(tag) => {
                let prop = self.parse_property(src, node, tag, &attrs, b, depth)?;
                b.add_prop(prop)
            }
            Item::Ref => self.parse_ref(src, node, &attrs, b),
            Item::Include => self.parse_include(src, node, &attrs, b, depth),
            Item::Default => {
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
            Item::Alias => {
                no_content(src, node)?;
                attrs.allow(&["id", "as"])?;
                let id = attrs.require("id")?;
                let new = attrs.require("as")?;
                let obj = self.resolve(&id.value, &id.loc)?;
                if new.value.is_empty() {
                    return Err(new.error(&attrs.tag, "must not be empty"));
                }
                self.check_new_id(&new.value, &new.loc)?;
                self.ids.insert(new.value.clone(), (obj, attrs.loc.clone()));
                Ok(())
            }
        }
    }

    /// The object declared with `id`.
    fn resolve(&self, id: &str, loc: &Loc) -> Result<Rc<Object>> {
        if let Some((obj, _)) = self.ids.get(id) {
            return Ok(obj.clone());
        }
        let msg = if self.open_ids.contains_key(id) {
            format!("id \"{id}\" refers to an object that contains this reference")
        } else {
            format!("unknown id \"{id}\" (objects must be declared before they are referenced)")
        };
        Err(InputError::at(loc, msg))
    }

    fn parse_ref(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        attrs: &Attrs,
        b: &mut Building,
    ) -> Result<()> {
        no_content(src, node)?;
        attrs.allow(&["id", "name"])?;
        let id = attrs.require("id")?;
        let obj = self.resolve(&id.value, &attrs.loc)?;
        obj.mark_referenced();
        let name = match attrs.get("name") {
            Some(a) if a.value.is_empty() => return Err(a.error(&attrs.tag, "must not be empty")),
            Some(a) => Some(b.param_name(&a.value)),
            None => None,
        };
        b.add_child(Child::new(name, obj, attrs.loc.clone(), true))
    }

    fn parse_include(
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
        let path = src.dir.join(&fname.value);
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
        let result = if root.tag_name().name() == "scene" {
            // The included scene's content is spliced in place of the <include>.
            Attrs::read(root, &isrc, &self.params)
                .and_then(|ra| {
                    ra.allow(&["version"])?;
                    check_version(&ra)
                })
                .and_then(|()| self.parse_body(&isrc, root, b, depth + 1))
        } else {
            self.parse_item(&isrc, root, b, depth + 1)
        };
        self.files.pop();
        result
    }

    /// Reads a property element.
    fn parse_property(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        tag: &str,
        a: &Attrs,
        b: &Building,
        depth: usize,
    ) -> Result<Prop> {
        let name = a.require("name")?;
        if name.value.is_empty() {
            return Err(name.error(&a.tag, "must not be empty"));
        }
        let value = match tag {
            "transform" => {
                a.allow(&["name"])?;
                Value::Transform(self.parse_transform(src, node, depth)?)
            }
            _ => {
                no_content(src, node)?;
                self.simple_value(tag, a)?
            }
        };
        Ok(Prop::new(b.param_name(&name.value), value, a.loc.clone()))
    }

    /// The value of a property element other than `<transform>`.
    fn simple_value(&self, tag: &str, a: &Attrs) -> Result<Value> {
        let t = a.tag.as_str();
        Ok(match tag {
            "float" | "integer" | "boolean" | "string" | "rgb" => {
                a.allow(&["name", "value"])?;
                let v = a.require("value")?;
                match tag {
                    "float" => Value::Float(v.float(t)?),
                    "integer" => Value::Integer(v.int(t)?),
                    "boolean" => Value::Boolean(v.boolean(t)?),
                    "string" => Value::String(v.value.clone()),
                    _ => Value::Rgb(v.vec3(t, true)?),
                }
            }
            "spectrum" => {
                a.allow(&["name", "value", "filename"])?;
                if let Some(f) = a.get("filename") {
                    return Err(f.error(t, "spectra are not supported (only <spectrum value=\"v\"/>, meaning grey): use <rgb>"));
                }
                let v = a.require("value")?;
                let items: Vec<&str> = super::values::split_list(&v.value).collect();
                match items.as_slice() {
                    [one] if !one.contains(':') => Value::Float(v.float(t)?),
                    _ => return Err(v.error(
                        t,
                        "spectra are not supported (only a single value, meaning grey): use <rgb>",
                    )),
                }
            }
            "point" | "vector" => {
                a.allow(&["name", "value", "x", "y", "z"])?;
                let v = transform::xyz(a, &["value"], 0.0, true)?
                    .ok_or_else(|| {
                        a.error(format!(
                            "<{t}> needs a \"value\" or \"x\"/\"y\"/\"z\" attributes"
                        ))
                    })?
                    .to_array();
                if tag == "point" {
                    Value::Point(v)
                } else {
                    Value::Vector(v)
                }
            }
            _ => unreachable!("not a simple property tag: {tag}"),
        })
    }

    /// Composes the operations inside a `<transform>` element (`M = op * M`).
    fn parse_transform(&self, src: &Source<'_>, node: Node<'_, '_>, depth: usize) -> Result<DMat4> {
        let mut m = DMat4::IDENTITY;
        for ch in node.children() {
            if !ch.is_element() {
                check_text(src, node, ch)?;
                continue;
            }
            let loc = src.loc(ch.range().start);
            if depth + 1 > MAX_DEPTH {
                return Err(InputError::at(
                    &loc,
                    format!("elements are nested deeper than {MAX_DEPTH} levels"),
                ));
            }
            let tag = ch.tag_name().name();
            if !transform::is_op(tag) {
                return Err(InputError::at(
                    &loc,
                    format!(
                        "<{tag}> is not allowed inside <transform> (expected translate, scale, rotate, matrix or lookat)"
                    ),
                ));
            }
            let a = Attrs::read(ch, src, &self.params)?;
            no_content(src, ch)?;
            m = transform::op_matrix(&a)? * m;
        }
        Ok(m)
    }
}

//! The normalized scene tree: objects, their properties and children, with locations.
//!
//! Every value is tagged with where it came from. Typed getters (in `getters.rs`) mark a
//! property as used, so that [`Object::check_unused`] can reject parameters nobody asked for,
//! as Mitsuba does.

use std::cell::Cell;
use std::fmt;
use std::path::PathBuf;
use std::rc::Rc;

use glam::DMat4;

use crate::error::{InputError, Loc};

/// What an object is (its element name, in Mitsuba vocabulary).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// `<scene>`: the root, or a nested scene inside a Nori `<test>`.
    Scene,
    /// `<integrator>`.
    Integrator,
    /// `<sensor>` (Nori: `<camera>`).
    Sensor,
    /// `<film>`.
    Film,
    /// `<sampler>`.
    Sampler,
    /// `<rfilter>` (reconstruction filter).
    RFilter,
    /// `<shape>` (Nori: `<mesh>`).
    Shape,
    /// `<bsdf>`.
    Bsdf,
    /// `<emitter>`.
    Emitter,
    /// `<texture>`.
    Texture,
    /// Nori's `<test>` (`chi2test`, `ttest`).
    Test,
    /// `<medium>` (a participating medium).
    Medium,
    /// `<phase>` (a medium's phase function).
    Phase,
    /// `<volume>` (a quantity varying through space: a heterogeneous medium's parameters).
    Volume,
}

impl Kind {
    /// All kinds.
    pub(crate) const ALL: [Kind; 14] = [
        Kind::Scene,
        Kind::Integrator,
        Kind::Sensor,
        Kind::Film,
        Kind::Sampler,
        Kind::RFilter,
        Kind::Shape,
        Kind::Bsdf,
        Kind::Emitter,
        Kind::Texture,
        Kind::Test,
        Kind::Medium,
        Kind::Phase,
        Kind::Volume,
    ];

    /// The Mitsuba element name (`"bsdf"`, `"rfilter"`, ...).
    pub fn tag(self) -> &'static str {
        match self {
            Kind::Scene => "scene",
            Kind::Integrator => "integrator",
            Kind::Sensor => "sensor",
            Kind::Film => "film",
            Kind::Sampler => "sampler",
            Kind::RFilter => "rfilter",
            Kind::Shape => "shape",
            Kind::Bsdf => "bsdf",
            Kind::Emitter => "emitter",
            Kind::Texture => "texture",
            Kind::Test => "test",
            Kind::Medium => "medium",
            Kind::Phase => "phase",
            Kind::Volume => "volume",
        }
    }

    /// The kind for a (Mitsuba) element name.
    pub(crate) fn from_tag(tag: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.tag() == tag)
    }
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.tag())
    }
}

/// A property value.
///
/// `<spectrum value="v"/>` is stored as `Float(v)`; [`Object::rgb`] reads a float as grey.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `<float>`.
    Float(f64),
    /// `<integer>`.
    Integer(i64),
    /// `<boolean>`.
    Boolean(bool),
    /// `<string>`.
    String(String),
    /// `<rgb>` (Nori: `<color>`).
    Rgb([f64; 3]),
    /// `<point>`.
    Point([f64; 3]),
    /// `<vector>`.
    Vector([f64; 3]),
    /// `<transform>`, already composed.
    Transform(DMat4),
}

impl Value {
    /// The type's name as used in messages (`"float"`, `"rgb"`, ...).
    pub(crate) fn type_name(&self) -> &'static str {
        match self {
            Value::Float(_) => "float",
            Value::Integer(_) => "integer",
            Value::Boolean(_) => "boolean",
            Value::String(_) => "string",
            Value::Rgb(_) => "rgb",
            Value::Point(_) => "point",
            Value::Vector(_) => "vector",
            Value::Transform(_) => "transform",
        }
    }
}

/// A named property of an object.
#[derive(Clone, Debug, PartialEq)]
pub struct Prop {
    /// The normalized name (`to_world`, never `toWorld`).
    pub name: String,
    /// The value.
    pub value: Value,
    /// Where the property element starts.
    pub loc: Loc,
    used: Cell<bool>,
}

impl Prop {
    /// A new, not yet used property.
    pub fn new(name: impl Into<String>, value: Value, loc: Loc) -> Self {
        Prop {
            name: name.into(),
            value,
            loc,
            used: Cell::new(false),
        }
    }

    /// Marks the property as used.
    pub fn mark_used(&self) {
        self.used.set(true);
    }

    /// Whether a getter asked for this property.
    pub(crate) fn is_used(&self) -> bool {
        self.used.get()
    }
}

/// One use of an object inside another: an inline declaration or a `<ref>`.
#[derive(Clone, Debug)]
pub struct Child {
    /// The per-use name: the `name` attribute of the nested element or of the `<ref>`
    /// (normalized like property names), if any.
    pub name: Option<String>,
    /// The object (a `<ref>` yields the same `Rc` as the declaration).
    pub obj: Rc<Object>,
    /// Where this use is (the nested element, or the `<ref>` element).
    pub loc: Loc,
    /// True when this use is a `<ref>` (or came from one).
    pub is_ref: bool,
    used: Cell<bool>,
}

impl Child {
    /// A new, not yet consumed child.
    pub fn new(name: Option<String>, obj: Rc<Object>, loc: Loc, is_ref: bool) -> Self {
        Child {
            name,
            obj,
            loc,
            is_ref,
            used: Cell::new(false),
        }
    }

    /// Marks the child as consumed by the builder.
    pub fn mark_used(&self) {
        self.used.set(true);
    }

    /// Whether the builder consumed this child.
    pub(crate) fn is_used(&self) -> bool {
        self.used.get()
    }
}

/// An object of the scene tree (`<scene>`, `<shape>`, `<bsdf>`, ...).
#[derive(Debug)]
pub struct Object {
    /// What it is.
    pub kind: Kind,
    /// The `type` attribute (`""` for a scene).
    pub plugin: String,
    /// The `id` attribute.
    pub id: Option<String>,
    /// The `name` attribute of the declaring element (see [`Child::name`] for per-use names).
    pub name: Option<String>,
    /// Where the element starts.
    pub loc: Loc,
    /// Properties, in file order; names are unique (also against named children).
    pub props: Vec<Prop>,
    /// Nested objects and resolved `<ref>`s, in file order.
    pub children: Vec<Child>,
    /// The folders relative file names are looked up in, first to last (see
    /// [`Object::resolve_file`]); shared by every object of a load.
    pub(crate) search: Rc<[PathBuf]>,
    /// On the root of a load: located warnings about the files themselves.
    pub(crate) load_warnings: Vec<String>,
    /// On the root of a load: where the world's origin was moved from (the camera's position)
    /// when the scene was recentred on its camera (`recentre.rs`), else zero.
    pub(crate) frame_origin: glam::DVec3,
    /// On the root of a load: whose conventions the scene is rendered with.
    pub(crate) dialect: super::conventions::Dialect,
    referenced: Cell<bool>,
}

impl Object {
    /// A new object (used by the parser and by tests).
    pub fn new(
        kind: Kind,
        plugin: impl Into<String>,
        id: Option<String>,
        name: Option<String>,
        loc: Loc,
        props: Vec<Prop>,
        children: Vec<Child>,
    ) -> Self {
        Object {
            kind,
            plugin: plugin.into(),
            id,
            name,
            loc,
            props,
            children,
            search: Rc::new([]),
            load_warnings: Vec::new(),
            frame_origin: glam::DVec3::ZERO,
            dialect: super::conventions::Dialect::Nori,
            referenced: Cell::new(false),
        }
    }

    /// `bsdf "diffuse"`, or `scene` for a scene: how messages name this object.
    pub fn describe(&self) -> String {
        if self.plugin.is_empty() {
            self.kind.tag().to_string()
        } else {
            format!("{} \"{}\"", self.kind, self.plugin)
        }
    }

    /// An error located at this object's element.
    pub fn error(&self, msg: impl Into<String>) -> InputError {
        InputError::at(&self.loc, msg)
    }

    /// The error for a required parameter that is absent:
    /// `file:line:col: missing parameter "radius" in shape "sphere"` (at this object).
    pub fn missing(&self, name: &str) -> InputError {
        self.error(format!(
            "missing parameter \"{name}\" in {}",
            self.describe()
        ))
    }

    /// Whether some `<ref>` refers to this object.
    pub(crate) fn is_referenced(&self) -> bool {
        self.referenced.get()
    }

    /// Records that a `<ref>` refers to this object.
    pub(crate) fn mark_referenced(&self) {
        self.referenced.set(true);
    }

    /// Whether a property or a named child called `name` exists (does not mark it used).
    pub fn has(&self, name: &str) -> bool {
        self.props.iter().any(|p| p.name == name)
            || self
                .children
                .iter()
                .any(|c| c.name.as_deref() == Some(name))
    }

    /// The property called `name`, marked as used.
    pub fn prop(&self, name: &str) -> Option<&Prop> {
        let p = self.props.iter().find(|p| p.name == name)?;
        p.mark_used();
        Some(p)
    }

    /// The child whose per-use name is `name`, marked as used.
    pub fn child(&self, name: &str) -> Option<&Child> {
        let c = self
            .children
            .iter()
            .find(|c| c.name.as_deref() == Some(name))?;
        c.mark_used();
        Some(c)
    }

    /// The children of one kind, in file order (not marked as used).
    pub fn children_of(&self, kind: Kind) -> impl Iterator<Item = &Child> + '_ {
        self.children.iter().filter(move |c| c.obj.kind == kind)
    }
}

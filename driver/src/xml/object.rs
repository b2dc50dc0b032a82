//! The normalized scene tree: objects, their properties and children, with locations.
//!
//! Every value is tagged with where it came from. Typed getters mark a property as used, so
//! that [`Object::check_unused`] can reject parameters nobody asked for, as Mitsuba does.

use std::cell::Cell;
use std::fmt;
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
}

impl Kind {
    /// All kinds.
    pub const ALL: [Kind; 11] = [
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
        }
    }

    /// The kind for a (Mitsuba) element name.
    pub fn from_tag(tag: &str) -> Option<Kind> {
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
    pub fn type_name(&self) -> &'static str {
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
    pub fn is_used(&self) -> bool {
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
    pub fn is_used(&self) -> bool {
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
    referenced: Cell<bool>,
}

type Result<T> = std::result::Result<T, InputError>;

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
    pub fn is_referenced(&self) -> bool {
        self.referenced.get()
    }

    /// Records that a `<ref>` refers to this object.
    pub fn mark_referenced(&self) {
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

    /// Looks up `name` for a getter expecting `expected` (`"a float"`): the used-marked
    /// property, or a located error when a named child object has that name.
    fn lookup(&self, name: &str, expected: &str) -> Result<Option<&Prop>> {
        if let Some(p) = self.prop(name) {
            return Ok(Some(p));
        }
        if let Some(c) = self
            .children
            .iter()
            .find(|c| c.name.as_deref() == Some(name))
        {
            c.mark_used();
            return Err(InputError::at(
                &c.loc,
                format!(
                    "parameter \"{name}\" of {} must be {expected}, found {} \"{}\"",
                    self.describe(),
                    c.obj.kind,
                    c.obj.plugin
                ),
            ));
        }
        Ok(None)
    }

    fn mismatch(&self, p: &Prop, expected: &str) -> InputError {
        InputError::at(
            &p.loc,
            format!(
                "parameter \"{}\" of {} must be {expected}, found {}",
                p.name,
                self.describe(),
                p.value.type_name()
            ),
        )
    }

    /// A float (an integer is accepted too), or `None` when absent.
    pub fn float_opt(&self, name: &str) -> Result<Option<f64>> {
        const WANT: &str = "a float";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Float(v) => Ok(Some(v)),
                Value::Integer(v) => Ok(Some(v as f64)),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// A float (an integer is accepted too), or `default` when absent.
    pub fn float(&self, name: &str, default: f64) -> Result<f64> {
        Ok(self.float_opt(name)?.unwrap_or(default))
    }

    /// An integer, or `None` when absent.
    pub fn integer_opt(&self, name: &str) -> Result<Option<i64>> {
        const WANT: &str = "an integer";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Integer(v) => Ok(Some(v)),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// An integer, or `default` when absent.
    pub fn integer(&self, name: &str, default: i64) -> Result<i64> {
        Ok(self.integer_opt(name)?.unwrap_or(default))
    }

    /// A boolean, or `None` when absent.
    pub fn boolean_opt(&self, name: &str) -> Result<Option<bool>> {
        const WANT: &str = "a boolean";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Boolean(v) => Ok(Some(v)),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// A boolean, or `default` when absent.
    pub fn boolean(&self, name: &str, default: bool) -> Result<bool> {
        Ok(self.boolean_opt(name)?.unwrap_or(default))
    }

    /// A string, or `None` when absent.
    pub fn string_opt(&self, name: &str) -> Result<Option<String>> {
        const WANT: &str = "a string";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match &p.value {
                Value::String(v) => Ok(Some(v.clone())),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// A string, or `default` when absent.
    pub fn string(&self, name: &str, default: &str) -> Result<String> {
        Ok(self
            .string_opt(name)?
            .unwrap_or_else(|| default.to_string()))
    }

    /// An rgb color (a float or integer means grey), or `None` when absent.
    pub fn rgb_opt(&self, name: &str) -> Result<Option<[f64; 3]>> {
        const WANT: &str = "an rgb color (or a float)";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Rgb(v) => Ok(Some(v)),
                Value::Float(v) => Ok(Some([v; 3])),
                Value::Integer(v) => Ok(Some([v as f64; 3])),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// An rgb color (a float or integer means grey), or `default` when absent.
    pub fn rgb(&self, name: &str, default: [f64; 3]) -> Result<[f64; 3]> {
        Ok(self.rgb_opt(name)?.unwrap_or(default))
    }

    /// A point (a `<vector>` is accepted too, as in Mitsuba), or `None` when absent.
    pub fn point_opt(&self, name: &str) -> Result<Option<[f64; 3]>> {
        const WANT: &str = "a point";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Point(v) | Value::Vector(v) => Ok(Some(v)),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// A point (a `<vector>` is accepted too), or `default` when absent.
    pub fn point(&self, name: &str, default: [f64; 3]) -> Result<[f64; 3]> {
        Ok(self.point_opt(name)?.unwrap_or(default))
    }

    /// A vector (a `<point>` is accepted too, as in Mitsuba), or `None` when absent.
    pub fn vector_opt(&self, name: &str) -> Result<Option<[f64; 3]>> {
        const WANT: &str = "a vector";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Point(v) | Value::Vector(v) => Ok(Some(v)),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// A vector (a `<point>` is accepted too), or `default` when absent.
    pub fn vector(&self, name: &str, default: [f64; 3]) -> Result<[f64; 3]> {
        Ok(self.vector_opt(name)?.unwrap_or(default))
    }

    /// A transform, or `None` when absent.
    pub fn transform_opt(&self, name: &str) -> Result<Option<DMat4>> {
        const WANT: &str = "a transform";
        match self.lookup(name, WANT)? {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Transform(m) => Ok(Some(m)),
                _ => Err(self.mismatch(p, WANT)),
            },
        }
    }

    /// A transform, or `default` when absent.
    pub fn transform(&self, name: &str, default: DMat4) -> Result<DMat4> {
        Ok(self.transform_opt(name)?.unwrap_or(default))
    }

    /// Fails on the first property no getter asked for, then on the first child the builder
    /// did not consume, e.g. `scene.xml:4:3: unused parameter "foo" in bsdf "diffuse"`.
    ///
    /// An inline declaration whose object some `<ref>` refers to counts as consumed (it was
    /// declared to be referenced).
    pub fn check_unused(&self) -> Result<()> {
        if let Some(p) = self.props.iter().find(|p| !p.is_used()) {
            return Err(InputError::at(
                &p.loc,
                format!("unused parameter \"{}\" in {}", p.name, self.describe()),
            ));
        }
        let unused = self
            .children
            .iter()
            .find(|c| !c.is_used() && (c.is_ref || !c.obj.is_referenced()));
        if let Some(c) = unused {
            let what = format!("{} \"{}\"", c.obj.kind, c.obj.plugin);
            let msg = match &c.name {
                Some(n) => format!("unused parameter \"{n}\" ({what}) in {}", self.describe()),
                None => format!("unused {what} in {}", self.describe()),
            };
            return Err(InputError::at(&c.loc, msg));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;
    use std::sync::Arc;

    fn loc(line: u32) -> Loc {
        Loc::new(Arc::new(PathBuf::from("s.xml")), line, 3)
    }

    fn obj() -> Object {
        let tex = Rc::new(Object::new(
            Kind::Texture,
            "checkerboard",
            None,
            None,
            loc(9),
            vec![],
            vec![],
        ));
        Object::new(
            Kind::Bsdf,
            "diffuse",
            None,
            None,
            loc(1),
            vec![
                Prop::new("f", Value::Float(0.5), loc(2)),
                Prop::new("i", Value::Integer(3), loc(3)),
                Prop::new("s", Value::String("x".into()), loc(4)),
                Prop::new("c", Value::Rgb([0.1, 0.2, 0.3]), loc(5)),
                Prop::new("p", Value::Point([1.0, 2.0, 3.0]), loc(6)),
                Prop::new("b", Value::Boolean(true), loc(7)),
                Prop::new("t", Value::Transform(DMat4::IDENTITY), loc(8)),
            ],
            vec![Child::new(Some("reflectance".into()), tex, loc(9), false)],
        )
    }

    #[test]
    fn getters_and_defaults() {
        let o = obj();
        assert_eq!(o.float("f", 0.0).unwrap(), 0.5);
        assert_eq!(o.float("i", 0.0).unwrap(), 3.0);
        assert_eq!(o.float("missing", 7.0).unwrap(), 7.0);
        assert_eq!(o.integer("i", 0).unwrap(), 3);
        assert_eq!(o.integer_opt("nope").unwrap(), None);
        assert_eq!(o.string("s", "").unwrap(), "x");
        assert_eq!(o.rgb("c", [0.0; 3]).unwrap(), [0.1, 0.2, 0.3]);
        assert_eq!(o.rgb("f", [0.0; 3]).unwrap(), [0.5; 3]);
        assert_eq!(o.vector("p", [0.0; 3]).unwrap(), [1.0, 2.0, 3.0]);
        assert!(o.boolean("b", false).unwrap());
        assert_eq!(o.transform_opt("t").unwrap(), Some(DMat4::IDENTITY));
        assert!(o.has("reflectance") && !o.has("zzz"));
        assert_eq!(
            o.missing("radius").to_string(),
            "s.xml:1:3: missing parameter \"radius\" in bsdf \"diffuse\""
        );
    }

    #[test]
    fn mismatch_is_located() {
        let o = obj();
        let e = o.float("s", 0.0).unwrap_err().to_string();
        assert_eq!(
            e,
            "s.xml:4:3: parameter \"s\" of bsdf \"diffuse\" must be a float, found string"
        );
        let e = o.integer("f", 0).unwrap_err().to_string();
        assert!(
            e.starts_with("s.xml:2:3: ") && e.ends_with("found float"),
            "{e}"
        );
        let e = o.rgb("reflectance", [0.0; 3]).unwrap_err().to_string();
        assert!(
            e.starts_with("s.xml:9:3: ") && e.contains("found texture \"checkerboard\""),
            "{e}"
        );
    }

    #[test]
    fn unused_reporting() {
        let o = obj();
        let e = o.check_unused().unwrap_err().to_string();
        assert_eq!(e, "s.xml:2:3: unused parameter \"f\" in bsdf \"diffuse\"");
        for n in ["f", "i", "s", "c", "p", "b", "t"] {
            o.prop(n).unwrap();
        }
        let e = o.check_unused().unwrap_err().to_string();
        assert_eq!(
            e,
            "s.xml:9:3: unused parameter \"reflectance\" (texture \"checkerboard\") in bsdf \"diffuse\""
        );
        assert!(o.child("reflectance").is_some());
        o.check_unused().unwrap();
    }
}

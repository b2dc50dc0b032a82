//! The typed property getters of [`Object`] and its check for unused parameters.
//!
//! Each getter marks the property it reads as used; [`Object::check_unused`] then rejects
//! whatever nobody read.

use glam::DMat4;

use super::object::{Object, Prop, Value};
use crate::error::InputError;

type Result<T> = std::result::Result<T, InputError>;

impl Object {
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
    pub(crate) fn float_opt(&self, name: &str) -> Result<Option<f64>> {
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
    pub(crate) fn integer_opt(&self, name: &str) -> Result<Option<i64>> {
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
    pub(crate) fn boolean_opt(&self, name: &str) -> Result<Option<bool>> {
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
    pub(crate) fn rgb_opt(&self, name: &str) -> Result<Option<[f64; 3]>> {
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
    pub(crate) fn point_opt(&self, name: &str) -> Result<Option<[f64; 3]>> {
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
    pub(crate) fn vector_opt(&self, name: &str) -> Result<Option<[f64; 3]>> {
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
    pub(crate) fn transform_opt(&self, name: &str) -> Result<Option<DMat4>> {
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
    use crate::error::Loc;
    use crate::xml::{Child, Kind};
    use std::path::PathBuf;
    use std::rc::Rc;
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

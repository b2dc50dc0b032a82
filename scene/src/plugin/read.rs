//! Reading a declared parameter from a parsed object: the declared default when the file does
//! not give it, the declared range checked with a located one-line error when it does. Texture
//! and index-of-refraction parameters are read by `materials::texture` and `materials::ior`.
use super::param::{Default, Param, Range};
use crate::error::InputError;
use crate::util::{at_prop, check_color, transform};
use crate::xml::Object;
use tessera_core::math::Transform;
use tessera_core::Color;

type Result<T> = std::result::Result<T, InputError>;

impl Param {
    /// The error for a value outside the declared range (`what` says the range).
    pub(crate) fn out_of_range(
        &self,
        obj: &Object,
        what: &str,
        found: impl std::fmt::Display,
    ) -> InputError {
        at_prop(
            obj,
            self.name,
            format!(
                "\"{}\" of {} must be {what}, found {found}",
                self.name,
                obj.describe()
            ),
        )
    }

    /// A float: the declared default, or the file's value checked against the declared range.
    pub(crate) fn read_f32(&self, obj: &Object) -> Result<f32> {
        match self.default {
            Default::Float(d) => self.read_f32_or(obj, d),
            Default::Required => {
                let v = obj
                    .float_opt(self.name)?
                    .ok_or_else(|| obj.missing(self.name))?;
                self.checked(obj, v, |v| self.range.contains(v), &self.describe_range())
            }
            other => unreachable!("\"{}\" has no float default ({other:?})", self.name),
        }
    }

    /// A float with a default computed by the builder (a [`Default::Note`]).
    pub(crate) fn read_f32_or(&self, obj: &Object, default: f64) -> Result<f32> {
        let v = obj.float(self.name, default)?;
        self.checked(obj, v, |v| self.range.contains(v), &self.describe_range())
    }

    /// A float that must pass `ok`, a rule involving other parameters ([`Range::Note`] says it).
    pub(crate) fn read_f32_where(
        &self,
        obj: &Object,
        default: f64,
        ok: impl Fn(f64) -> bool,
    ) -> Result<f32> {
        let v = obj.float(self.name, default)?;
        self.checked(obj, v, |v| v.is_finite() && ok(v), &self.describe_range())
    }

    /// A float, `None` when absent ([`Default::Absent`]).
    pub(crate) fn read_f32_opt(&self, obj: &Object) -> Result<Option<f32>> {
        match obj.float_opt(self.name)? {
            None => Ok(None),
            Some(v) => self
                .checked(obj, v, |v| self.range.contains(v), &self.describe_range())
                .map(Some),
        }
    }

    fn checked(&self, obj: &Object, v: f64, ok: impl Fn(f64) -> bool, what: &str) -> Result<f32> {
        if !ok(v) || !(v as f32).is_finite() {
            return Err(self.out_of_range(obj, what, v));
        }
        Ok(v as f32)
    }

    /// An integer within the declared range.
    pub(crate) fn read_i64(&self, obj: &Object) -> Result<i64> {
        let v = match self.default {
            Default::Integer(d) => obj.integer(self.name, d)?,
            Default::Required => obj
                .integer_opt(self.name)?
                .ok_or_else(|| obj.missing(self.name))?,
            other => unreachable!("\"{}\" has no integer default ({other:?})", self.name),
        };
        if !self.range.contains(v as f64) {
            return Err(self.out_of_range(obj, &self.describe_range(), v));
        }
        Ok(v)
    }

    /// An integer that must pass `ok` ([`Range::Note`] says the rule).
    pub(crate) fn read_i64_where(&self, obj: &Object, ok: impl Fn(i64) -> bool) -> Result<i64> {
        match self.default {
            Default::Integer(d) => self.read_i64_or(obj, d, ok),
            other => unreachable!("\"{}\" has no integer default ({other:?})", self.name),
        }
    }

    /// An integer with a default computed by the builder (a [`Default::Note`]), which must
    /// pass `ok`.
    pub(crate) fn read_i64_or(
        &self,
        obj: &Object,
        default: i64,
        ok: impl Fn(i64) -> bool,
    ) -> Result<i64> {
        let v = obj.integer(self.name, default)?;
        if !ok(v) {
            return Err(self.out_of_range(obj, &self.describe_range(), v));
        }
        Ok(v)
    }

    /// A boolean.
    pub(crate) fn read_bool(&self, obj: &Object) -> Result<bool> {
        match self.default {
            Default::Boolean(d) => obj.boolean(self.name, d),
            other => unreachable!("\"{}\" has no boolean default ({other:?})", self.name),
        }
    }

    /// A string (the declared default, or a located "missing" error when it is required).
    pub(crate) fn read_string(&self, obj: &Object) -> Result<String> {
        match self.default {
            Default::Str(d) => obj.string(self.name, d),
            Default::Required => obj
                .string_opt(self.name)?
                .ok_or_else(|| obj.missing(self.name)),
            other => unreachable!("\"{}\" has no string default ({other:?})", self.name),
        }
    }

    /// One of the declared names: the file's value (or the default), returned as declared.
    pub(crate) fn read_choice(&self, obj: &Object) -> Result<&'static str> {
        match (self.read_choice_opt(obj)?, self.default) {
            (Some(name), _) => Ok(name),
            (None, Default::Str(d)) => Ok(d),
            (None, Default::Required) => Err(obj.missing(self.name)),
            (None, other) => unreachable!("\"{}\" has no string default ({other:?})", self.name),
        }
    }

    /// One of the declared names as the file gives it, `None` when absent (the builder then
    /// applies a default of its own, a [`Default::Note`]).
    pub(crate) fn read_choice_opt(&self, obj: &Object) -> Result<Option<&'static str>> {
        let Some(s) = obj.string_opt(self.name)? else {
            return Ok(None);
        };
        let (names, any_case) = match self.range {
            Range::OneOf(n) => (n, false),
            Range::OneOfAnyCase(n) => (n, true),
            other => unreachable!("\"{}\" is not a choice ({other:?})", self.name),
        };
        let found = names.iter().find(|n| {
            if any_case {
                n.eq_ignore_ascii_case(&s)
            } else {
                **n == s
            }
        });
        found.copied().map(Some).ok_or_else(|| {
            at_prop(
                obj,
                self.name,
                format!(
                    "unknown {} \"{s}\" in {} (known: {})",
                    self.name,
                    obj.describe(),
                    names.join(", ")
                ),
            )
        })
    }

    /// A colour: finite and non-negative, and in [0, 1] when the range is [`Range::Unit`].
    pub fn read_color(&self, obj: &Object) -> Result<Color> {
        let c = match self.default {
            Default::Rgb(d) => obj.rgb(self.name, d)?,
            Default::Required => obj.rgb_opt(self.name)?.ok_or_else(|| {
                obj.error(format!(
                    "{} needs the parameter \"{}\"",
                    obj.describe(),
                    self.name
                ))
            })?,
            other => unreachable!("\"{}\" has no colour default ({other:?})", self.name),
        };
        let c = check_color(obj, self.name, c)?;
        if self.range == Range::Unit && c.max_element() > 1.0 {
            return Err(self.out_of_range(obj, "in [0, 1]", c));
        }
        Ok(c)
    }

    /// A colour the file may leave out (`None` then), checked as [`Param::read_color`] checks.
    pub(crate) fn read_color_opt(&self, obj: &Object) -> Result<Option<Color>> {
        let Some(c) = obj.rgb_opt(self.name)? else {
            return Ok(None);
        };
        let c = check_color(obj, self.name, c)?;
        if self.range == Range::Unit && c.max_element() > 1.0 {
            return Err(self.out_of_range(obj, "in [0, 1]", c));
        }
        Ok(Some(c))
    }

    /// A transform, checked invertible and finite (identity when absent).
    pub(crate) fn read_transform(&self, obj: &Object) -> Result<Transform> {
        transform(obj, self.name)
    }
}

//! A plugin parameter declared as data: its name, type, default, valid range and one line of
//! meaning. The loader reads every parameter through its declaration (`plugin::read`), so the
//! default and the range check it applies, the list of parameters an unused-parameter error
//! names, and the reference documentation (`plugin::doc`) all come from this one place.
use std::fmt;

/// What a parameter holds, as a scene file writes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamType {
    /// `<float>` (an `<integer>` is accepted too).
    Float,
    /// `<integer>`.
    Integer,
    /// `<boolean>`.
    Boolean,
    /// `<string>`.
    String,
    /// `<string>`, one of a fixed set of names ([`Range::OneOf`]).
    Choice,
    /// `<rgb>` (a `<float>` means grey).
    Rgb,
    /// `<rgb>` or `<float>`, or a nested or referenced `<texture>`.
    Texture,
    /// `<rgb>` or `<float>`, or a nested or referenced `<volume>`.
    Volume,
    /// An index of refraction: `<float>`, or a `<string>` naming a material.
    Ior,
    /// `<point>` (a `<vector>` is accepted too).
    Point,
    /// `<vector>` (a `<point>` is accepted too).
    Vector,
    /// `<transform>`.
    Transform,
}

impl ParamType {
    /// How the reference names the type.
    pub fn describe(self) -> &'static str {
        match self {
            ParamType::Float => "float",
            ParamType::Integer => "integer",
            ParamType::Boolean => "boolean",
            ParamType::String => "string",
            ParamType::Choice => "string",
            ParamType::Rgb => "rgb",
            ParamType::Texture => "rgb or texture",
            ParamType::Volume => "rgb or volume",
            ParamType::Ior => "float or material name",
            ParamType::Point => "point",
            ParamType::Vector => "vector",
            ParamType::Transform => "transform",
        }
    }
}

/// The value a parameter takes when the file does not give it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Default {
    /// The file must give it.
    Required,
    /// Nothing: the plugin does without (its meaning says what then).
    Absent,
    /// A number.
    Float(f64),
    /// An integer.
    Integer(i64),
    /// A boolean.
    Boolean(bool),
    /// A string (a choice, a material name, a length like `"50mm"`).
    Str(&'static str),
    /// A colour.
    Rgb([f64; 3]),
    /// The identity transform.
    Identity,
    /// A value that depends on other parameters, said in words.
    Note(&'static str),
}

impl fmt::Display for Default {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Default::Required => write!(f, "required"),
            Default::Absent => write!(f, "none"),
            Default::Float(v) => write!(f, "{v}"),
            Default::Integer(v) => write!(f, "{v}"),
            Default::Boolean(v) => write!(f, "{v}"),
            Default::Str(s) => write!(f, "\"{s}\""),
            Default::Rgb([r, g, b]) if r == g && g == b => write!(f, "{r}"),
            Default::Rgb([r, g, b]) => write!(f, "({r}, {g}, {b})"),
            Default::Identity => write!(f, "identity"),
            Default::Note(s) => write!(f, "{s}"),
        }
    }
}

/// The values a parameter accepts. Numbers must be finite in every range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// Any finite value (any string, any transform the reader accepts).
    Any,
    /// `>= 0` (for colours and textures: every channel).
    NonNegative,
    /// `> 0`.
    Positive,
    /// In `[0, 1]` (for colours and textures: every channel).
    Unit,
    /// Between two bounds, each closed or open.
    Between {
        /// Lower bound.
        lo: f64,
        /// Whether `lo` itself is accepted.
        lo_closed: bool,
        /// Upper bound.
        hi: f64,
        /// Whether `hi` itself is accepted.
        hi_closed: bool,
    },
    /// One of these names.
    OneOf(&'static [&'static str]),
    /// One of these names, in any letter case (as Mitsuba 3 reads microfacet distributions).
    OneOfAnyCase(&'static [&'static str]),
    /// A rule that involves other parameters, said in words (checked by the plugin's builder).
    Note(&'static str),
}

impl Range {
    /// `[lo, hi]`.
    pub const fn closed(lo: f64, hi: f64) -> Range {
        Range::Between {
            lo,
            lo_closed: true,
            hi,
            hi_closed: true,
        }
    }

    /// `(lo, hi]`.
    pub(crate) const fn open_closed(lo: f64, hi: f64) -> Range {
        Range::Between {
            lo,
            lo_closed: false,
            hi,
            hi_closed: true,
        }
    }

    /// `(lo, hi)`.
    pub const fn open(lo: f64, hi: f64) -> Range {
        Range::Between {
            lo,
            lo_closed: false,
            hi,
            hi_closed: false,
        }
    }

    /// Whether a number is in the range (always for the ranges that are not numeric).
    pub fn contains(&self, v: f64) -> bool {
        if !v.is_finite() {
            return false;
        }
        match *self {
            Range::NonNegative | Range::Unit if v < 0.0 => false,
            Range::Unit => v <= 1.0,
            Range::Positive => v > 0.0,
            Range::Between {
                lo,
                lo_closed,
                hi,
                hi_closed,
            } => (v > lo || (lo_closed && v == lo)) && (v < hi || (hi_closed && v == hi)),
            _ => true,
        }
    }

    /// The words an error or the reference uses: "positive", "in [0, 1]", ...
    pub fn describe(&self) -> String {
        match self {
            Range::Any => "any".into(),
            Range::NonNegative => "non-negative".into(),
            Range::Positive => "positive".into(),
            Range::Unit => "in [0, 1]".into(),
            Range::Between {
                lo,
                lo_closed,
                hi,
                hi_closed,
            } => format!(
                "in {}{}, {}{}",
                if *lo_closed { '[' } else { '(' },
                number(*lo),
                number(*hi),
                if *hi_closed { ']' } else { ')' }
            ),
            Range::OneOf(names) => format!("one of {}", names.join(", ")),
            Range::OneOfAnyCase(names) => format!("one of {} (any case)", names.join(", ")),
            Range::Note(s) => (*s).into(),
        }
    }
}

/// A bound as the reference writes it: `0.5`, `64`, `1e6`.
fn number(v: f64) -> String {
    if v.abs() >= 1e5 {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// One declared parameter of a plugin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Param {
    /// Name in the scene file (Mitsuba 3's; other dialects' names are translated on reading).
    pub name: &'static str,
    /// What it holds.
    pub ty: ParamType,
    /// Its value when absent.
    pub default: Default,
    /// The values it accepts.
    pub range: Range,
    /// One line of meaning.
    pub doc: &'static str,
    /// The unit of a number (`"degrees"`), or empty.
    pub unit: &'static str,
    /// Accepted for compatibility but without effect in Tessera: a file that gives it gets a
    /// located warning.
    pub ignored: bool,
}

impl Param {
    /// A float parameter.
    pub const fn float(name: &'static str, default: f64, range: Range, doc: &'static str) -> Self {
        Param::new(name, ParamType::Float, Default::Float(default), range, doc)
    }

    /// An integer parameter.
    pub const fn integer(
        name: &'static str,
        default: i64,
        range: Range,
        doc: &'static str,
    ) -> Self {
        Param::new(
            name,
            ParamType::Integer,
            Default::Integer(default),
            range,
            doc,
        )
    }

    /// A boolean parameter.
    pub const fn boolean(name: &'static str, default: bool, doc: &'static str) -> Self {
        Param::new(
            name,
            ParamType::Boolean,
            Default::Boolean(default),
            Range::Any,
            doc,
        )
    }

    /// A string naming one of `names` (`default` among them).
    pub const fn choice(
        name: &'static str,
        default: &'static str,
        names: &'static [&'static str],
        doc: &'static str,
    ) -> Self {
        Param::new(
            name,
            ParamType::Choice,
            Default::Str(default),
            Range::OneOf(names),
            doc,
        )
    }

    /// A colour or texture parameter with a constant default.
    pub const fn texture(
        name: &'static str,
        default: [f64; 3],
        range: Range,
        doc: &'static str,
    ) -> Self {
        Param::new(name, ParamType::Texture, Default::Rgb(default), range, doc)
    }

    /// An index of refraction whose default is a named material.
    pub const fn ior(name: &'static str, default: &'static str, doc: &'static str) -> Self {
        Param::new(
            name,
            ParamType::Ior,
            Default::Str(default),
            Range::Positive,
            doc,
        )
    }

    /// A colour parameter.
    pub const fn rgb(
        name: &'static str,
        default: Default,
        range: Range,
        doc: &'static str,
    ) -> Self {
        Param::new(name, ParamType::Rgb, default, range, doc)
    }

    /// A required file name, relative to the scene file (`what` says which files).
    pub const fn file(what: &'static str, doc: &'static str) -> Self {
        Param::new(
            "filename",
            ParamType::String,
            Default::Required,
            Range::Note(what),
            doc,
        )
    }

    /// A transform parameter (identity when absent).
    pub const fn transform(name: &'static str, doc: &'static str) -> Self {
        Param::new(
            name,
            ParamType::Transform,
            Default::Identity,
            Range::Any,
            doc,
        )
    }

    /// Any parameter, spelled out.
    pub const fn new(
        name: &'static str,
        ty: ParamType,
        default: Default,
        range: Range,
        doc: &'static str,
    ) -> Self {
        Param {
            name,
            ty,
            default,
            range,
            doc,
            unit: "",
            ignored: false,
        }
    }

    /// The same parameter, accepted without effect (a file that gives it gets a warning).
    pub const fn ignored(self) -> Self {
        Param {
            ignored: true,
            ..self
        }
    }

    /// The same parameter with a unit.
    pub(crate) const fn with_unit(self, unit: &'static str) -> Self {
        Param { unit, ..self }
    }

    /// The range in words, with the unit: "in (0, 180] degrees".
    pub(crate) fn describe_range(&self) -> String {
        if self.unit.is_empty() {
            self.range.describe()
        } else {
            format!("{} {}", self.range.describe(), self.unit)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_hold_their_bounds_as_declared() {
        assert!(Range::Unit.contains(0.0) && Range::Unit.contains(1.0));
        assert!(!Range::Unit.contains(1.0001) && !Range::Unit.contains(-0.0001));
        assert!(!Range::Positive.contains(0.0) && Range::Positive.contains(1e-30));
        assert!(Range::NonNegative.contains(0.0) && !Range::NonNegative.contains(-1.0));
        let r = Range::open_closed(0.0, 64.0);
        assert!(!r.contains(0.0) && r.contains(64.0) && !r.contains(64.5));
        let r = Range::open(0.0, 180.0);
        assert!(!r.contains(180.0) && r.contains(179.9));
        for r in [Range::Any, Range::Positive, Range::closed(-1.0, 1.0)] {
            assert!(!r.contains(f64::NAN) && !r.contains(f64::INFINITY));
        }
        assert_eq!(Range::open_closed(0.0, 64.0).describe(), "in (0, 64]");
        assert_eq!(Range::closed(0.0, 1e6).describe(), "in [0, 1e6]");
    }
}

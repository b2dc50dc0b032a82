//! Test support: checks a family's declarations against what its builders do. For every plugin
//! and every parameter whose default can be written in a file, giving that default explicitly
//! must build the same thing as leaving it out, and must not be reported unused: so each
//! declared default is the one the builder applies, and each declared parameter is read. An
//! undeclared parameter must be refused with a message that lists the declared ones.
use super::{Default, Param, ParamType, Plugin};
use crate::error::InputError;
use crate::xml::{Kind, Object};
use std::fmt::Debug;
use std::path::Path;

/// The XML element that gives `p` its default value, or `None` when the default cannot be
/// written (required, absent, computed, identity).
pub(crate) fn default_element(p: &Param) -> Option<String> {
    let (tag, value) = match (p.ty, p.default) {
        (_, Default::Float(v)) => ("float", format!("{v}")),
        (_, Default::Integer(v)) => ("integer", format!("{v}")),
        (_, Default::Boolean(v)) => ("boolean", format!("{v}")),
        (ParamType::Ior | ParamType::String | ParamType::Choice, Default::Str(s)) => {
            ("string", s.to_string())
        }
        (_, Default::Rgb([r, g, b])) => ("rgb", format!("{r}, {g}, {b}")),
        _ => return None,
    };
    Some(format!("<{tag} name=\"{}\" value=\"{value}\"/>", p.name))
}

/// Builds the first object of `kind` in `<scene version="3.0.0">` + `body`.
fn build_one<T, B>(
    kind: Kind,
    body: &str,
    build: impl Fn(&Object) -> Result<T, InputError>,
    plugin: &Plugin<B>,
) -> Result<T, InputError> {
    let text = format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n");
    let root = crate::xml::load_str(&text, Path::new("/nowhere/check.xml"), &[])?;
    let child = root
        .children_of(kind)
        .next()
        .ok_or_else(|| root.error(format!("no <{}> in the snippet", kind.tag())))?;
    let built = build(&child.obj)?;
    plugin.check_unused(&child.obj)?;
    Ok(built)
}

/// Runs the checks for every plugin of `family` (elements `<tag type=...>` of `kind`), built
/// by `build`. `inner(name)` is what a minimal object of that plugin must contain besides the
/// parameter under test (nested objects, required parameters); `skip` lists `(plugin,
/// parameter)` pairs whose explicit default changes the meaning (one of a pair that must be
/// given together).
pub(crate) fn check_family<T: Debug, B>(
    family: &[Plugin<B>],
    kind: Kind,
    build: impl Fn(&Object) -> Result<T, InputError> + Copy,
    inner: impl Fn(&str) -> String,
    skip: &[(&str, &str)],
) {
    let tag = kind.tag();
    for plugin in family {
        let name = plugin.name;
        let element =
            |extra: &str| format!("<{tag} type=\"{name}\">{extra}{}</{tag}>", inner(name));
        let plain = build_one(kind, &element(""), build, plugin)
            .unwrap_or_else(|e| panic!("{name} with defaults: {e}"));
        let plain = format!("{plain:?}");
        for p in plugin.params {
            if skip.contains(&(name, p.name)) {
                continue;
            }
            let Some(given) = default_element(p) else {
                continue;
            };
            let built = build_one(kind, &element(&given), build, plugin)
                .unwrap_or_else(|e| panic!("{name} with {given}: {e}"));
            assert_eq!(
                format!("{built:?}"),
                plain,
                "{name}: {given} builds something else than the declared default"
            );
        }
        let e = build_one(
            kind,
            &element("<float name=\"no_such_parameter\" value=\"1\"/>"),
            build,
            plugin,
        )
        .map(|_| ())
        .expect_err("an undeclared parameter is refused");
        let e = e.to_string();
        assert!(
            e.contains("unused parameter \"no_such_parameter\""),
            "{name}: {e}"
        );
        for p in plugin.params {
            assert!(
                e.contains(p.name),
                "{name}: the error does not list {}: {e}",
                p.name
            );
        }
    }
}

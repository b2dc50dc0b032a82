//! Reading a test file's settings: located errors, the significance level, counts, number
//! lists and the BSDF children, shared by every kind of test.
use super::case::MIN_SIGNIFICANCE;
use tessera_scene::error::{InputError, Loc};
use tessera_scene::xml::{Kind, Object};

/// The location of property `name` of `obj`, or of `obj` itself when absent.
pub(crate) fn prop_loc(obj: &Object, name: &str) -> Loc {
    obj.props
        .iter()
        .find(|p| p.name == name)
        .map_or_else(|| obj.loc.clone(), |p| p.loc.clone())
}

/// An error located at property `name` of `obj` (or at `obj` when absent).
pub(crate) fn at_prop(obj: &Object, name: &str, msg: impl Into<String>) -> InputError {
    InputError::at(&prop_loc(obj, name), msg)
}

/// `significanceLevel` (default 0.01), in `[MIN_SIGNIFICANCE, 1)`.
pub(crate) fn significance(root: &Object) -> Result<f64, InputError> {
    let level = root.float("significance_level", 0.01)?;
    if !(MIN_SIGNIFICANCE..1.0).contains(&level) {
        return Err(at_prop(
            root,
            "significance_level",
            format!(
                "\"significanceLevel\" must be at least {MIN_SIGNIFICANCE:e} and below 1, \
                 found {level}"
            ),
        ));
    }
    Ok(level)
}

/// An integer parameter with a default, at least `min`.
pub(crate) fn count(
    root: &Object,
    name: &str,
    nori_name: &str,
    default: i64,
    min: i64,
) -> Result<usize, InputError> {
    let v = root.integer(name, default)?;
    if v < min {
        return Err(at_prop(
            root,
            name,
            format!("\"{nori_name}\" must be at least {min}, found {v}"),
        ));
    }
    usize::try_from(v).map_err(|_| at_prop(root, name, format!("\"{nori_name}\" is too large")))
}

/// A required list of numbers in a string parameter (separated by commas and/or white space,
/// as Nori tokenizes), with the location of the property.
pub(crate) fn number_list(
    root: &Object,
    name: &str,
    nori_name: &str,
) -> Result<(Vec<f64>, Loc), InputError> {
    let text = root
        .string_opt(name)?
        .ok_or_else(|| root.missing(nori_name))?;
    let loc = prop_loc(root, name);
    let values: Vec<f64> = text
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(InputError::at(
                &loc,
                format!("\"{nori_name}\" holds \"{s}\", not a finite number"),
            )),
        })
        .collect::<Result<_, _>>()?;
    if values.is_empty() {
        return Err(InputError::at(&loc, format!("\"{nori_name}\" is empty")));
    }
    Ok((values, loc))
}

/// The `<bsdf>` children of a BSDF test, built, with labels (`diffuse (file:line:col)`);
/// any other child is a located error.
pub(crate) fn bsdf_children(
    root: &Object,
) -> Result<Vec<(String, tessera_core::bsdf::Bsdf)>, InputError> {
    let mut out = Vec::new();
    for c in &root.children {
        if c.obj.kind != Kind::Bsdf {
            return Err(InputError::at(
                &c.loc,
                format!(
                    "a BSDF {} holds <bsdf> elements only, found <{}>",
                    root.plugin,
                    c.obj.kind.tag()
                ),
            ));
        }
        c.mark_used();
        let bsdf = tessera_scene::build_bsdf_object(&c.obj)?;
        out.push((format!("{} ({})", c.obj.plugin, c.loc), bsdf));
    }
    if out.is_empty() {
        return Err(root.error(format!("the {} holds no <bsdf>", root.plugin)));
    }
    Ok(out)
}

/// `(x, y, z)` with four decimals, for labels.
pub(crate) fn fmt_dir(v: glam::Vec3) -> String {
    format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z)
}

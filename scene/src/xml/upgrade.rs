//! Mitsuba 0.x files (`<scene version="0.6.0">`, any version below 2.0): the renames Mitsuba 3's
//! parser applies to every object of such a file before using it.
//!
//! Parameter names in camelCase become snake_case; Tessera does that for every file (see
//! `dialect.rs`), so this holds the rest of Mitsuba's table: a diffuse BSDF's
//! `diffuse_reflectance` is its `reflectance`, and `uoffset`, `voffset`, `uscale`, `vscale`
//! become one `to_uv` transform, scale(uscale, vscale) * translate(uoffset, voffset). Files of
//! version 2.0 and later, and Nori files (no version), are left as they are.

use glam::{DMat4, DVec3};

use super::building::Building;
use super::object::{Kind, Prop, Value};
use crate::error::InputError;

/// A file version, `(major, minor, patch)`.
pub(super) type Version = (u32, u32, u32);

/// Parses a version attribute already checked by `check_version` (missing parts are 0).
pub(super) fn parse_version(v: &str) -> Option<Version> {
    let mut parts = v.split('.').map(|p| p.parse::<u32>().ok());
    let major = parts.next()??;
    let minor = parts.next().unwrap_or(Some(0))?;
    let patch = parts.next().unwrap_or(Some(0))?;
    Some((major, minor, patch))
}

/// Whether objects of a file with this version attribute are upgraded.
pub(super) fn needs_upgrade(version: Option<Version>) -> bool {
    version.is_some_and(|v| v < (2, 0, 0))
}

/// Applies the upgrade table to an object read from a file of version < 2.0.
pub(super) fn upgrade(b: &mut Building) -> Result<(), InputError> {
    if b.kind == Kind::Bsdf && b.plugin == "diffuse" {
        rename(b, "diffuse_reflectance", "reflectance")?;
    }
    let mut offset = DVec3::ZERO;
    let mut scale = DVec3::ONE;
    let mut first = None;
    for (name, slot) in [
        ("uoffset", &mut offset.x),
        ("voffset", &mut offset.y),
        ("uscale", &mut scale.x),
        ("vscale", &mut scale.y),
    ] {
        let Some(i) = b.props.iter().position(|p| p.name == name) else {
            continue;
        };
        let p = b.props.remove(i);
        b.names.remove(name);
        *slot = match p.value {
            Value::Float(x) => x,
            Value::Integer(x) => x as f64,
            ref other => {
                return Err(InputError::at(
                    &p.loc,
                    format!("\"{name}\" must be a float, found {}", other.type_name()),
                ))
            }
        };
        first = first.or(Some(p.loc));
    }
    if let Some(loc) = first {
        let m = DMat4::from_scale(scale) * DMat4::from_translation(offset);
        b.add_prop(Prop::new("to_uv", Value::Transform(m), loc))?;
    }
    Ok(())
}

/// Renames a property or named child `from` to `to`, if present.
fn rename(b: &mut Building, from: &str, to: &str) -> Result<(), InputError> {
    let Some(loc) = b.names.remove(from) else {
        return Ok(());
    };
    b.claim_name(to, &loc)?;
    for p in b.props.iter_mut().filter(|p| p.name == from) {
        p.name = to.to_string();
    }
    for c in b
        .children
        .iter_mut()
        .filter(|c| c.name.as_deref() == Some(from))
    {
        c.name = Some(to.to_string());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions() {
        assert_eq!(parse_version("0.6.0"), Some((0, 6, 0)));
        assert_eq!(parse_version("3"), Some((3, 0, 0)));
        assert!(needs_upgrade(parse_version("0.5")));
        assert!(needs_upgrade(parse_version("1.9.9")));
        assert!(!needs_upgrade(parse_version("2.0.0")));
        assert!(!needs_upgrade(parse_version("3.0.0")));
        assert!(!needs_upgrade(None));
    }
}

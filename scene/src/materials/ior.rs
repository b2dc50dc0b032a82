//! Indices of refraction: a number or one of Mitsuba 3's named materials.
use super::super::util::{at_prop, Result};
use crate::plugin::{Default, Param};
use crate::xml::{Object, Value};

/// Named indices of refraction (at 589 nm), as Mitsuba 3 accepts them.
pub(crate) const NAMED: &[(&str, f64)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// The declared index of refraction `p` of `obj` (its default names a material).
pub(crate) fn read_ior(obj: &Object, p: &Param) -> Result<f64> {
    let Default::Str(default) = p.default else {
        unreachable!("index \"{}\" has no named default", p.name)
    };
    ior(obj, p.name, default)
}

/// The indices `int` and `ext` of `obj` and their ratio `int / ext` (computed in double
/// precision, then rounded), which must be finite and positive.
pub(crate) fn read_eta(obj: &Object, int: &Param, ext: &Param) -> Result<(f64, f64, f32)> {
    let int_ior = read_ior(obj, int)?;
    let ext_ior = read_ior(obj, ext)?;
    let eta = (int_ior / ext_ior) as f32;
    if !(eta.is_finite() && eta > 0.0) {
        return Err(at_prop(
            obj,
            int.name,
            format!(
                "\"{}\" / \"{}\" of {} is out of range",
                int.name,
                ext.name,
                obj.describe()
            ),
        ));
    }
    Ok((int_ior, ext_ior, eta))
}

/// Refuses equal indices `int_ior` and `ext_ior` (a rough interface between equal media has
/// no reflection and an undefined refraction; Mitsuba 3 refuses it too).
pub(crate) fn indices_differ<T: PartialEq + std::fmt::Display>(
    obj: &Object,
    int_ior: T,
    ext_ior: T,
) -> Result<()> {
    if int_ior == ext_ior {
        return Err(at_prop(
            obj,
            "int_ior",
            format!(
                "\"int_ior\" and \"ext_ior\" of {} must differ (both are {int_ior})",
                obj.describe()
            ),
        ));
    }
    Ok(())
}

/// The index of refraction `name` of `obj`: a `<float>` or a `<string>` naming a material;
/// `default` names the value used when absent. Must be finite and positive.
pub fn ior(obj: &Object, name: &str, default: &str) -> Result<f64> {
    let lookup = |s: &str| NAMED.iter().find(|(n, _)| *n == s).map(|&(_, v)| v);
    let v = match obj.prop(name).map(|p| &p.value) {
        Some(Value::String(s)) => {
            obj.prop(name).unwrap().mark_used();
            match lookup(s.as_str()) {
                Some(v) => v,
                None => {
                    let names: Vec<&str> = NAMED.iter().map(|(n, _)| *n).collect();
                    return Err(at_prop(
                        obj,
                        name,
                        format!(
                            "\"{name}\" of {}: unknown material \"{s}\" (known: {})",
                            obj.describe(),
                            names.join(", ")
                        ),
                    ));
                }
            }
        }
        Some(_) => obj.float(name, 1.0)?,
        None => lookup(default).expect("default index names a known material"),
    };
    if !(v.is_finite() && v > 0.0) {
        return Err(at_prop(
            obj,
            name,
            format!(
                "\"{name}\" of {} must be positive, found {v}",
                obj.describe()
            ),
        ));
    }
    Ok(v)
}

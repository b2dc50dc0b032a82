//! The operations inside `<transform>`: translate, scale, rotate, matrix, lookat.
//!
//! Each operation is a 4x4 matrix; `<transform>` applies them in file order, each new one
//! multiplied on the left (`M = op * M`), as Mitsuba and Nori do.

use glam::{DMat3, DMat4, DVec3};
use tessera_core::math::Norm;

use super::attrs::Attrs;
use crate::error::InputError;

type Result<T> = std::result::Result<T, InputError>;

/// Whether `tag` is a transform operation element.
pub(crate) fn is_op(tag: &str) -> bool {
    matches!(tag, "translate" | "scale" | "rotate" | "matrix" | "lookat")
}

/// Reads a three-component attribute group: `value="x y z"` (or a single number when
/// `allow_one`), or separate `x`, `y`, `z` attributes, missing ones taking `default`.
/// `None` when none of them is present.
pub fn xyz(
    a: &Attrs,
    value_names: &[&str],
    default: f64,
    allow_one: bool,
) -> Result<Option<DVec3>> {
    let vattr = value_names.iter().find_map(|n| a.get(n));
    let has_xyz = a.any(&["x", "y", "z"]);
    if let Some(v) = vattr {
        if has_xyz {
            return Err(a.error(format!(
                "<{}> takes either \"{}\" or \"x\"/\"y\"/\"z\" attributes, not both",
                a.tag, v.name
            )));
        }
        return Ok(Some(DVec3::from_array(v.vec3(&a.tag, allow_one)?)));
    }
    if !has_xyz {
        return Ok(None);
    }
    let mut out = [default; 3];
    for (i, n) in ["x", "y", "z"].iter().enumerate() {
        if let Some(at) = a.get(n) {
            out[i] = at.float(&a.tag)?;
        }
    }
    Ok(Some(DVec3::from_array(out)))
}

/// Rodrigues' rotation matrix `cos I + (1 - cos) a a^T + sin [a]x` with the axis `a` as
/// given: a rotation when `a` has unit length, and what Mitsuba 3 builds from a `<rotate>`
/// element whatever its length (it does not normalise the axis).
fn rotation_as_given(a: DVec3, radians: f64) -> DMat4 {
    let (s, c) = radians.sin_cos();
    let k = 1.0 - c;
    // Columns of the 3x3 part.
    let x = DVec3::new(
        c + k * a.x * a.x,
        k * a.x * a.y + s * a.z,
        k * a.x * a.z - s * a.y,
    );
    let y = DVec3::new(
        k * a.x * a.y - s * a.z,
        c + k * a.y * a.y,
        k * a.y * a.z + s * a.x,
    );
    let z = DVec3::new(
        k * a.x * a.z + s * a.y,
        k * a.y * a.z - s * a.x,
        c + k * a.z * a.z,
    );
    DMat4::from_mat3(DMat3::from_cols(x, y, z))
}

/// The matrix of one operation element (its attributes already read); located warnings go to
/// `warnings`.
pub(crate) fn op_matrix(a: &Attrs, warnings: &mut Vec<String>) -> Result<DMat4> {
    let tag = a.tag.as_str();
    match tag {
        "translate" => {
            a.allow(&["value", "x", "y", "z"])?;
            let t = xyz(a, &["value"], 0.0, true)?.ok_or_else(|| {
                a.error("<translate> needs a \"value\" or \"x\"/\"y\"/\"z\" attributes")
            })?;
            Ok(DMat4::from_translation(t))
        }
        "scale" => {
            a.allow(&["value", "x", "y", "z"])?;
            let s = xyz(a, &["value"], 1.0, true)?.ok_or_else(|| {
                a.error("<scale> needs a \"value\" or \"x\"/\"y\"/\"z\" attributes")
            })?;
            Ok(DMat4::from_scale(s))
        }
        "rotate" => {
            a.allow(&["angle", "axis", "value", "x", "y", "z"])?;
            if a.get("axis").is_some() && a.get("value").is_some() {
                return Err(a.error("<rotate> takes either \"axis\" or \"value\", not both"));
            }
            let angle = a.require("angle")?.float(tag)?;
            let axis = xyz(a, &["axis", "value"], 0.0, false)?.ok_or_else(|| {
                a.error("<rotate> needs an axis: \"axis\" or \"x\"/\"y\"/\"z\" attributes")
            })?;
            if axis.length_squared() == 0.0 {
                return Err(a.error("<rotate> has a zero rotation axis"));
            }
            let unit = (axis.length_squared() - 1.0).abs() <= 1e-9;
            if unit {
                return Ok(DMat4::from_axis_angle(axis.unit(), angle.to_radians()));
            }
            warnings.push(format!(
                "{}: the <rotate> axis {:?} is not of unit length; as Mitsuba 3 does, it is used \
                 as given, so the matrix also scales and shears (normalise the axis for a \
                 rotation)",
                a.loc,
                axis.to_array()
            ));
            Ok(rotation_as_given(axis, angle.to_radians()))
        }
        "matrix" => {
            a.allow(&["value"])?;
            let at = a.require("value")?;
            let v = at.floats(tag)?;
            match v.len() {
                16 => Ok(DMat4::from_cols_slice(&v).transpose()),
                9 => Ok(DMat4::from_mat3(DMat3::from_cols_slice(&v).transpose())),
                n => Err(at.error(
                    tag,
                    &format!("has {n} numbers, expected 16 (or 9), row-major"),
                )),
            }
        }
        "lookat" => {
            a.allow(&["origin", "target", "up"])?;
            let origin = DVec3::from_array(a.require("origin")?.vec3(tag, false)?);
            let target = DVec3::from_array(a.require("target")?.vec3(tag, false)?);
            let dir = target - origin;
            if dir.length_squared() == 0.0 {
                return Err(a.error("<lookat> has the same origin and target"));
            }
            let dir = dir.unit();
            let up = match a.get("up") {
                Some(u) => DVec3::from_array(u.vec3(tag, false)?),
                None => coordinate_system(dir),
            };
            let left = up.cross(dir);
            if left.length_squared() <= 1e-20 * up.length_squared() {
                return Err(a.error(
                    "<lookat> has an \"up\" vector that is zero or parallel to the view direction",
                ));
            }
            let left = left.unit();
            let new_up = dir.cross(left);
            Ok(DMat4::from_cols(
                left.extend(0.0),
                new_up.extend(0.0),
                dir.extend(0.0),
                origin.extend(1.0),
            ))
        }
        _ => Err(a.error(format!("unknown transform operation <{tag}>"))),
    }
}

/// A unit vector perpendicular to unit `n` (Duff et al. 2017), used as the default up.
fn coordinate_system(n: DVec3) -> DVec3 {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    DVec3::new(b, sign + n.y * n.y * a, -n.y)
}

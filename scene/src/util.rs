//! Conversions shared by the builders: located numeric checks, transforms, colours.
use crate::error::InputError;
use crate::xml::Object;
use glam::{DMat4, Mat4, Vec3};
use tessera_core::math::Transform;
use tessera_core::Color;

pub type Result<T> = std::result::Result<T, InputError>;

/// A transform parameter (identity when absent), checked invertible and finite.
pub fn transform(obj: &Object, name: &str) -> Result<Transform> {
    let Some(m) = obj.transform_opt(name)? else {
        return Ok(Transform::IDENTITY);
    };
    to_transform(obj, name, m)
}

/// A checked f32 transform from an f64 matrix (inverse computed in f64).
pub(crate) fn to_transform(obj: &Object, name: &str, m: DMat4) -> Result<Transform> {
    let loc = obj
        .prop(name)
        .map(|p| p.loc.clone())
        .unwrap_or_else(|| obj.loc.clone());
    let det = m.determinant();
    if !m.is_finite() || !det.is_finite() || det.abs() < 1e-30 {
        return Err(InputError::at(
            &loc,
            format!(
                "\"{name}\" of {} is not an invertible transform",
                obj.describe()
            ),
        ));
    }
    let inv = m.inverse();
    let (mf, invf) = (m.as_mat4(), inv.as_mat4());
    if !mf.is_finite() || !invf.is_finite() || mf == Mat4::ZERO {
        return Err(InputError::at(
            &loc,
            format!(
                "\"{name}\" of {} is out of single-precision range",
                obj.describe()
            ),
        ));
    }
    Ok(Transform { m: mf, inv: invf })
}

/// Converts an rgb value to a colour, checked finite and non-negative (located at `name`).
pub(crate) fn check_color(obj: &Object, name: &str, c: [f64; 3]) -> Result<Color> {
    let v = Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32);
    if !v.is_finite() || v.min_element() < 0.0 {
        return Err(at_prop(
            obj,
            name,
            format!(
                "\"{name}\" of {} must be finite and non-negative",
                obj.describe()
            ),
        ));
    }
    Ok(v)
}

/// An error located at a property (or the object when the property is absent).
pub fn at_prop(obj: &Object, name: &str, msg: String) -> InputError {
    match obj.props.iter().find(|p| p.name == name) {
        Some(p) => InputError::at(&p.loc, msg),
        None => obj.error(msg),
    }
}

/// Converts a point from f64.
pub fn vec3(p: [f64; 3]) -> Vec3 {
    Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32)
}

//! Texture-valued parameters: a constant (`<rgb>` or `<float>`) or a nested `<texture>`.
use super::super::util::{at_prop, Result};
use crate::xml::Object;
use glam::Vec3;
use tessera_core::texture::Texture;

/// The texture parameter `name` of `obj` (constant `default` when absent). With `unit`, every
/// value must lie in `[0, 1]` (reflectances, weights); otherwise only non-negative.
pub fn texture(obj: &Object, name: &str, default: [f64; 3], unit: bool) -> Result<Texture> {
    let c = obj.rgb(name, default)?;
    let v = Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32);
    let ok = v.is_finite() && v.min_element() >= 0.0 && (!unit || v.max_element() <= 1.0);
    if !ok {
        let range = if unit {
            "in [0, 1]"
        } else {
            "finite and non-negative"
        };
        return Err(at_prop(
            obj,
            name,
            format!("\"{name}\" of {} must be {range}", obj.describe()),
        ));
    }
    Ok(Texture::Constant(v))
}

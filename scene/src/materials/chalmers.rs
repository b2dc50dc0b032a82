//! Chalmers' path-tracer tutorial materials: `blinnphong` and `blinnphong_metal` (its
//! `LinearBlend` is `blend`, built in `basic.rs`).
//!
//! - `blinnphong`: `shininess` (float >= 0, default 25), `r0` or `fresnel` (float in [0, 1],
//!   default 0.04; not both), at most one nested bsdf (the layer below; none: nothing below).
//! - `blinnphong_metal`: `color` (rgb or texture in [0, 1], default 0.5), `shininess`, `r0` or
//!   `fresnel` as above.
use super::super::util::{at_prop, float_checked};
use super::texture::texture;
use super::{nested_bsdfs, Result};
use crate::xml::Object;
use tessera_core::bsdf::{BlinnPhong, BlinnPhongMetal, Bsdf};

/// Default Blinn-Phong exponent.
pub const DEFAULT_SHININESS: f64 = 25.0;
/// Default Schlick reflectance at normal incidence (a dielectric of index 1.5).
pub const DEFAULT_R0: f64 = 0.04;

/// Builds the plugins of this file.
pub fn build(obj: &Object) -> Result<Bsdf> {
    let shininess = float_checked(
        obj,
        "shininess",
        DEFAULT_SHININESS,
        |s| (0.0..=1e6).contains(&s),
        "in [0, 1e6]",
    )?;
    if obj.has("r0") && obj.has("fresnel") {
        return Err(at_prop(
            obj,
            "fresnel",
            format!(
                "{} takes \"r0\" or its alias \"fresnel\", not both",
                obj.describe()
            ),
        ));
    }
    let r0_name = if obj.has("fresnel") { "fresnel" } else { "r0" };
    let r0 = float_checked(
        obj,
        r0_name,
        DEFAULT_R0,
        |r| (0.0..=1.0).contains(&r),
        "in [0, 1]",
    )?;
    Ok(match obj.plugin.as_str() {
        "blinnphong" => {
            let base = nested_bsdfs(obj, 0, 1)?.pop().map(Box::new);
            Bsdf::BlinnPhong(BlinnPhong::new(shininess, r0, base))
        }
        "blinnphong_metal" => {
            nested_bsdfs(obj, 0, 0)?;
            Bsdf::BlinnPhongMetal(BlinnPhongMetal::new(
                texture(obj, "color", [0.5; 3], true)?,
                shininess,
                r0,
            ))
        }
        other => return Err(obj.error(format!("bsdf \"{other}\" is not implemented yet"))),
    })
}

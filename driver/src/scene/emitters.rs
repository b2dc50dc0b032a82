//! `<emitter>` objects: `area` (nested in a shape), `constant` and `point` (in the scene).
//!
//! `area`: `radiance` (rgb, required). `constant`: `radiance` (rgb, default 1). `point`:
//! `intensity` (rgb, default 1), `position` (point) or `to_world` (its translation).
use super::util::{color, color_required, transform, vec3, Result};
use crate::xml::Object;
use tessera_core::emitter::{AreaLight, ConstantEnv, Emitter, PointLight};

/// An area light on shape `shape`.
pub fn build_area(obj: &Object, shape: u32) -> Result<Emitter> {
    if obj.plugin != "area" {
        return Err(obj.error(format!(
            "a shape can only carry an \"area\" emitter, found \"{}\"",
            obj.plugin
        )));
    }
    let radiance = color_required(obj, "radiance")?;
    obj.check_unused()?;
    Ok(Emitter::Area(AreaLight { shape, radiance }))
}

/// An emitter declared at scene level.
pub fn build_scene_emitter(obj: &Object) -> Result<Emitter> {
    let e = match obj.plugin.as_str() {
        "constant" => Emitter::Constant(ConstantEnv {
            radiance: color(obj, "radiance", [1.0; 3])?,
        }),
        "point" => {
            let intensity = color(obj, "intensity", [1.0; 3])?;
            let position = match obj.point_opt("position")? {
                Some(p) => vec3(p),
                None => transform(obj, "to_world")?.point(glam::Vec3::ZERO),
            };
            Emitter::Point(PointLight {
                position,
                intensity,
            })
        }
        "area" => return Err(obj.error("an area emitter must be nested in a shape")),
        other => {
            return Err(obj.error(format!(
                "unknown emitter \"{other}\" (known: area, constant, point)"
            )))
        }
    };
    obj.check_unused()?;
    Ok(e)
}

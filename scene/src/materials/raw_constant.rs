//! The `rawconstant` texture plugin: one value everywhere, taken as written, as Mitsuba 3.9.1's
//! `rawconstant` (no colour conversion; in an RGB renderer a colour is already its own value).
//! Its `value` is a float (the same in every channel) or a vector (one value per channel), e.g.
//! the flat normal `0.5, 0.5, 1` of a `normalmap`. Mitsuba checks no range; here the value
//! obeys the parameter it feeds (in [0, 1] for a reflectance, non-negative otherwise), as every
//! constant does.
use super::super::util::at_prop;
use super::texture_plugin::TexturePlugin;
use crate::error::InputError;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::Value;
use glam::Vec3;
use tessera_core::texture::Texture;

const VALUE: Param = Param::new(
    "value",
    ParamType::Vector,
    Default::Required,
    Range::Note("a float or a vector; in [0, 1] for a reflectance or weight, else non-negative"),
    "the value, the same in every channel for a float",
);

/// `rawconstant`.
pub(crate) const RAW_CONSTANT: TexturePlugin = Plugin {
    name: "rawconstant",
    aliases: &[],
    doc: "A constant value without colour conversion (a float, or a vector of three).",
    params: &[VALUE],
    nested: "",
    build: |obj, unit| {
        let Some(p) = obj.prop(VALUE.name) else {
            return Err(obj.error(format!(
                "{} needs its parameter \"value\" (a float or a vector)",
                obj.describe()
            )));
        };
        let v = match p.value {
            Value::Float(x) => Vec3::splat(x as f32),
            Value::Integer(x) => Vec3::splat(x as f32),
            Value::Vector(v) | Value::Point(v) | Value::Rgb(v) => {
                Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
            }
            _ => {
                return Err(InputError::at(
                    &p.loc,
                    format!(
                        "parameter \"value\" of {} must be a float or a vector, found {}",
                        obj.describe(),
                        p.value.type_name()
                    ),
                ))
            }
        };
        let ok = v.is_finite() && v.min_element() >= 0.0 && (!unit || v.max_element() <= 1.0);
        if !ok {
            let want = if unit {
                "in [0, 1]"
            } else {
                "finite and non-negative"
            };
            return Err(at_prop(
                obj,
                VALUE.name,
                format!("\"value\" of {} must be {want} here", obj.describe()),
            ));
        }
        Ok(Texture::Constant(v))
    },
};

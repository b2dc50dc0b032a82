//! `area`: emission from the surface of the shape that carries it, the same everywhere or read
//! from a texture over the shape's uv.
use super::EmitterPlugin;
use crate::materials::texture::texture;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use tessera_core::emitter::{AreaLight, Emitter};
use tessera_core::texture::Texture;

const RADIANCE: Param = Param::new(
    "radiance",
    ParamType::Texture,
    Default::Required,
    Range::NonNegative,
    "emitted radiance, the same in every direction on the front side; a texture is looked \
     up at the surface's uv",
);

/// `area`.
pub(crate) const AREA: EmitterPlugin = Plugin {
    name: "area",
    aliases: &[],
    doc: "A diffuse area light on a shape's front side; nested in a `<shape>`, or declared \
          with an id and `<ref>`'d from shapes (each shape that refers to it emits).",
    params: &[RADIANCE],
    nested: "",
    build: |obj, shape| {
        let Some(shape) = shape else {
            return Err(obj.error(
                "an area emitter must be nested in a shape or referenced from one with <ref>",
            ));
        };
        let is_texture = obj.has(RADIANCE.name) && obj.prop(RADIANCE.name).is_none();
        if is_texture {
            return Ok(Emitter::Area(
                match texture(obj, RADIANCE.name, [0.0; 3], false)? {
                    Texture::Constant(c) => AreaLight::new(shape, c),
                    t => AreaLight::textured(shape, t),
                },
            ));
        }
        Ok(Emitter::Area(AreaLight::new(
            shape,
            RADIANCE.read_color(obj)?,
        )))
    },
};

//! `area`: emission from the surface of the shape that carries it.
use super::EmitterPlugin;
use crate::plugin::{Default, Param, Plugin, Range};
use tessera_core::emitter::{AreaLight, Emitter};

const RADIANCE: Param = Param::rgb(
    "radiance",
    Default::Required,
    Range::NonNegative,
    "emitted radiance, the same in every direction on the front side",
);

/// `area`.
pub const AREA: EmitterPlugin = Plugin {
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
        Ok(Emitter::Area(AreaLight::new(
            shape,
            RADIANCE.read_color(obj)?,
        )))
    },
};

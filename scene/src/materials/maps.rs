//! `normalmap` (Mitsuba 3 names and defaults): an adapter that tilts the shading frame of a
//! nested BSDF by a tangent-space normal texture.
use super::texture::texture;
use super::{nested_bsdfs, BsdfPlugin, Result};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::perturbed::PerturbOptions;
use tessera_core::bsdf::{Bsdf, NormalMap};

const NORMALMAP: Param = Param::new(
    "normalmap",
    ParamType::Texture,
    Default::Absent,
    Range::NonNegative,
    "tangent-space normals as colours (n + 1) / 2 (give the bitmap raw=\"true\")",
);
/// `flip_invalid_normals` of the normal-perturbing adapters.
const FLIP_INVALID_NORMALS: Param = Param::boolean(
    "flip_invalid_normals",
    true,
    "mirror the tangential part of a perturbed normal that faces away from the viewer",
);
/// `use_shadowing_function` of the normal-perturbing adapters.
const USE_SHADOWING_FUNCTION: Param = Param::boolean(
    "use_shadowing_function",
    true,
    "attenuate by the bump-terminator shadowing term of Estevez et al. 2019",
);

fn options(obj: &Object) -> Result<PerturbOptions> {
    Ok(PerturbOptions {
        flip_invalid_normals: FLIP_INVALID_NORMALS.read_bool(obj)?,
        use_shadowing_function: USE_SHADOWING_FUNCTION.read_bool(obj)?,
    })
}

/// `normalmap`.
pub(crate) const NORMALMAP_PLUGIN: BsdfPlugin = Plugin {
    name: "normalmap",
    aliases: &[],
    doc: "Normal mapping: the nested model is evaluated in a shading frame whose normal is read \
          from an RGB texture in tangent space (the frame's first tangent follows dp/du).",
    params: &[NORMALMAP, FLIP_INVALID_NORMALS, USE_SHADOWING_FUNCTION],
    nested: "exactly one `<bsdf>`",
    build: |obj, nest| {
        if !obj.has(NORMALMAP.name) {
            return Err(obj.missing(NORMALMAP.name));
        }
        let normalmap = texture(obj, NORMALMAP.name, [0.5, 0.5, 1.0], false)?;
        let nested = nested_bsdfs(obj, 1, 1, nest)?
            .pop()
            .expect("one nested bsdf");
        Ok(Bsdf::NormalMap(NormalMap {
            normalmap,
            nested: Box::new(nested),
            options: options(obj)?,
        }))
    },
};

//! `normalmap` and `bumpmap` (Mitsuba 3 names and defaults): adapters that tilt the shading
//! frame of a nested BSDF by a tangent-space normal texture or by a height texture's gradient.
use super::texture::{build_texture, texture};
use super::{nested_bsdfs, BsdfPlugin, Result};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::{Kind, Object};
use tessera_core::bsdf::perturbed::PerturbOptions;
use tessera_core::bsdf::{Bsdf, BumpMap, NormalMap};
use tessera_core::texture::Texture;

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

const SCALE: Param = Param::float(
    "scale",
    1.0,
    Range::Any,
    "multiplies the height read from the texture",
);

/// The one nested `<texture>` of a `bumpmap` (any name), which must be a bitmap: Mitsuba 3.9.1
/// has the gradient `bumpmap` reads for bitmaps only.
fn height_texture(obj: &Object) -> Result<Texture> {
    let kids: Vec<_> = obj.children_of(Kind::Texture).collect();
    let [child] = kids.as_slice() else {
        return Err(obj.error(format!(
            "{} needs exactly one nested texture (the height), found {}",
            obj.describe(),
            kids.len()
        )));
    };
    child.mark_used();
    let t = build_texture(&child.obj, false)?;
    match t {
        Texture::Bitmap(_) => Ok(t),
        _ => Err(crate::error::InputError::at(
            &child.loc,
            format!(
                "the height of {} must be a bitmap texture, found {} (bumpmap reads the \
                 texture's gradient, which Mitsuba 3.9.1 has for bitmaps only)",
                obj.describe(),
                child.obj.describe()
            ),
        )),
    }
}

/// `bumpmap`.
pub(crate) const BUMPMAP_PLUGIN: BsdfPlugin = Plugin {
    name: "bumpmap",
    aliases: &[],
    doc: "Bump mapping: the nested model is evaluated in a shading frame tilted by the uv \
          gradient of a height field, scale times a bitmap's luminance (give the bitmap \
          raw=\"true\"): dp/du and dp/dv get the gradient's components along the normal.",
    params: &[SCALE, FLIP_INVALID_NORMALS, USE_SHADOWING_FUNCTION],
    nested: "exactly one `<bsdf>` and one `<texture>` (the height, a `bitmap`; any name)",
    build: |obj, nest| {
        let height = height_texture(obj)?;
        let scale = SCALE.read_f32(obj)?;
        let nested = nested_bsdfs(obj, 1, 1, nest)?
            .pop()
            .expect("one nested bsdf");
        Ok(Bsdf::BumpMap(BumpMap {
            height,
            scale,
            nested: Box::new(nested),
            options: options(obj)?,
        }))
    },
};

//! Mitsuba 3's polarization plugins `pplastic` and `polarizer` (its names and defaults), as
//! Mitsuba 3's unpolarized (RGB) variants render them: Tessera carries no polarization state,
//! so what only polarized light would see (the polarizer's angle) is accepted with a warning.
use super::super::util::at_prop;
use super::conductor::{
    textured_microfacet, ALPHA_TEXTURE, ALPHA_U_TEXTURE, ALPHA_V_TEXTURE, DISTRIBUTION,
    SAMPLE_VISIBLE, SPECULAR_REFLECTANCE,
};
use super::ior::{indices_differ, read_ior};
use super::plastic::{DIFFUSE_REFLECTANCE, EXT_IOR, INT_IOR};
use super::texture::{read_texture, texture};
use super::{BsdfPlugin, Nest, Result};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, PolarizedPlastic, Polarizer};
use tessera_core::texture::Texture;

const ETA: Param = Param::new(
    "eta",
    ParamType::Texture,
    Default::Absent,
    Range::Positive,
    "relative index of refraction int_ior / ext_ior, given instead of the two indices",
);

/// `pplastic`.
pub(crate) const PPLASTIC: BsdfPlugin = Plugin {
    name: "pplastic",
    aliases: &[],
    doc: "Mitsuba 3's polarized plastic as its RGB variants render it: a rough dielectric \
          reflection (Beckmann or GGX, isotropic or anisotropic) plus a diffuse term attenuated \
          by the Fresnel transmittance into and out of the surface, simply added (no \
          interreflection between the two, unlike roughplastic). One-sided. The specular term \
          is sampled with probability s / (d + s) of the textures' means (s = 1 without \
          specular_reflectance). eta and the roughness may be textures, read as scalars (a \
          bitmap's luminance). Stricter than Mitsuba 3 where it would compute nonsense: \
          alpha must be positive (Mitsuba raises it to 1e-4; Tessera too below 1e-4), eta \
          positive, and ext_ior is refused beside eta (Mitsuba leaves it unreferenced).",
    params: &[
        DIFFUSE_REFLECTANCE,
        SPECULAR_REFLECTANCE,
        INT_IOR,
        EXT_IOR,
        ETA,
        DISTRIBUTION,
        ALPHA_TEXTURE,
        ALPHA_U_TEXTURE,
        ALPHA_V_TEXTURE,
        SAMPLE_VISIBLE,
    ],
    nested: "",
    build: build_pplastic,
};

fn build_pplastic(obj: &Object, _: Nest) -> Result<Bsdf> {
    let diffuse = read_texture(obj, &DIFFUSE_REFLECTANCE)?;
    let specular = read_texture(obj, &SPECULAR_REFLECTANCE)?;
    let eta = relative_index(obj)?;
    let (distr, roughness) = textured_microfacet(obj)?;
    Ok(Bsdf::PolarizedPlastic(PolarizedPlastic::new(
        diffuse, specular, eta, distr, roughness,
    )))
}

/// `eta`, or `int_ior / ext_ior` (in single precision, as Mitsuba 3 divides them).
fn relative_index(obj: &Object) -> Result<Texture> {
    if obj.has(ETA.name) {
        if let Some(other) = [INT_IOR.name, EXT_IOR.name]
            .into_iter()
            .find(|n| obj.has(n))
        {
            return Err(at_prop(
                obj,
                other,
                format!(
                    "{} takes either \"eta\" or \"int_ior\"/\"ext_ior\", not both",
                    obj.describe()
                ),
            ));
        }
        let eta = texture(obj, ETA.name, [1.5; 3], false)?;
        if let Texture::Constant(c) = &eta {
            if !(c.min_element() > 0.0) {
                return Err(ETA.out_of_range(obj, "positive", c.min_element()));
            }
        }
        return Ok(eta);
    }
    let int_ior = read_ior(obj, &INT_IOR)? as f32;
    let ext_ior = read_ior(obj, &EXT_IOR)? as f32;
    indices_differ(obj, int_ior, ext_ior)?;
    let eta = int_ior / ext_ior;
    if !(eta.is_finite() && eta > 0.0) {
        return Err(at_prop(
            obj,
            INT_IOR.name,
            format!(
                "the indices of {} give no usable ratio ({int_ior} / {ext_ior})",
                obj.describe()
            ),
        ));
    }
    Ok(Texture::constant(eta))
}

const THETA: Param = Param::new(
    "theta",
    ParamType::Texture,
    Default::Float(0.0),
    Range::Any,
    "has no effect: the angle of the transmission axis only matters to polarized light",
)
.with_unit("degrees")
.ignored();
const TRANSMITTANCE: Param = Param::texture(
    "transmittance",
    [1.0; 3],
    Range::NonNegative,
    "factor on the light that passes (which is half of the incident unpolarized light)",
);
const POLARIZING: Param = Param::boolean(
    "polarizing",
    true,
    "has no effect: Mitsuba 3's RGB variants pass half the light whether or not it polarizes",
)
.ignored();

/// `polarizer`.
pub(crate) const POLARIZER: BsdfPlugin = Plugin {
    name: "polarizer",
    aliases: &[],
    doc: "Mitsuba 3's linear polarizer as its RGB variants render it: a sheet that light passes \
          straight through (both sides), keeping half of it times the transmittance. A delta \
          pass-through like mask's: emitters behind it are reached by continuing the path, not \
          by emitter sampling, as in Mitsuba 3.",
    params: &[THETA, TRANSMITTANCE, POLARIZING],
    nested: "",
    build: build_polarizer,
};

fn build_polarizer(obj: &Object, _: Nest) -> Result<Bsdf> {
    // Read so that a malformed value is still refused where it is (any sign is an angle).
    match obj.child(THETA.name) {
        Some(c) if obj.prop(THETA.name).is_none() => c.mark_used(),
        _ => {
            THETA.read_f32(obj)?;
        }
    }
    POLARIZING.read_bool(obj)?;
    let transmittance = read_texture(obj, &TRANSMITTANCE)?;
    Ok(Bsdf::Polarizer(Polarizer { transmittance }))
}

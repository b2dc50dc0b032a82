//! `principled` (Mitsuba 3): Burley's Disney BSDF, which Mitsuba's Blender exporter writes for
//! every Principled BSDF node. Names, defaults and lobe switches as in Mitsuba 3.9.1: a lobe
//! whose weight the file does not give, or gives as the float 0, is off.
use super::super::util::at_prop;
use super::texture::texture;
use super::{BsdfPlugin, Nest, Result};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::{Object, Value};
use tessera_core::bsdf::{Bsdf, Principled, PrincipledIndex, PrincipledParams, SamplingRates};
use tessera_core::texture::Texture;

/// A scalar weight in `[0, 1]` that may be a texture, with a float default.
pub(super) const fn weight(name: &'static str, default: f64, doc: &'static str) -> Param {
    Param::new(
        name,
        ParamType::Texture,
        Default::Float(default),
        Range::Unit,
        doc,
    )
}

const BASE_COLOR: Param = Param::texture(
    "base_color",
    [0.5; 3],
    Range::Unit,
    "colour of the diffuse, metallic, tinted and transmitted light",
);
pub(super) const ROUGHNESS: Param = weight(
    "roughness",
    0.5,
    "roughness of the main specular lobes (GGX alpha = roughness^2, at least 1e-3) and of the retro-reflection",
);
pub(super) const ANISOTROPIC: Param = weight(
    "anisotropic",
    0.0,
    "anisotropy of the main lobes (0 isotropic); stretches alpha by sqrt(1 - 0.9 anisotropic)",
);
const METALLIC: Param = weight(
    "metallic",
    0.0,
    "blend toward a metal whose Schlick reflectance is the base colour",
);
const SPEC_TRANS: Param = weight(
    "spec_trans",
    0.0,
    "weight of the rough transmission (glass) among the non-metallic part",
);
const ETA: Param = Param::new(
    "eta",
    ParamType::Float,
    Default::Note("from specular"),
    Range::Positive,
    "relative index of refraction (inside over outside); give eta or specular, not both",
);
const SPECULAR: Param = Param::float(
    "specular",
    0.5,
    Range::Between {
        lo: 0.0,
        lo_closed: true,
        hi: 12.5,
        hi_closed: false,
    },
    "Blender's specular level, the index eta = 2 / (1 - sqrt(0.08 specular)) - 1 (used without eta)",
);
pub(super) const SPEC_TINT: Param = weight(
    "spec_tint",
    0.0,
    "tint of the dielectric reflection toward the base colour's hue",
);
const SHEEN: Param = weight(
    "sheen",
    0.0,
    "weight of the grazing sheen (cloth) of the non-metallic part",
);
pub(super) const SHEEN_TINT: Param = weight(
    "sheen_tint",
    0.0,
    "tint of the sheen toward the base colour's hue",
);
pub(super) const FLATNESS: Param = weight(
    "flatness",
    0.0,
    "blend of the diffuse toward Hanrahan-Krueger's flattened subsurface approximation",
);
const CLEARCOAT: Param = weight(
    "clearcoat",
    0.0,
    "weight of the clear coating (a second, isotropic specular lobe)",
);
const CLEARCOAT_GLOSS: Param = weight(
    "clearcoat_gloss",
    0.0,
    "gloss of the clear coating: its GTR1 roughness goes from 0.1 (0) to 0.001 (1)",
);
pub(super) const DIFFUSE_RATE: Param = Param::float(
    "diffuse_reflectance_sampling_rate",
    1.0,
    Range::NonNegative,
    "relative rate at which the diffuse lobe is sampled",
);
const SPECULAR_RATE: Param = Param::float(
    "main_specular_sampling_rate",
    1.0,
    Range::NonNegative,
    "relative rate at which the main specular lobes are sampled",
);
const CLEARCOAT_RATE: Param = Param::float(
    "clearcoat_sampling_rate",
    1.0,
    Range::NonNegative,
    "relative rate at which the clearcoat lobe is sampled",
);

/// `principled`.
pub(crate) const PRINCIPLED: BsdfPlugin = Plugin {
    name: "principled",
    aliases: &[],
    doc: "Burley's Disney BSDF as Mitsuba 3 writes it: diffuse with retro-reflection and sheen, \
          anisotropic GGX reflection blended toward a metal, rough transmission, and a clearcoat. \
          Mitsuba's Blender exporter writes it for every Principled BSDF node.",
    params: &[
        BASE_COLOR,
        ROUGHNESS,
        ANISOTROPIC,
        METALLIC,
        SPEC_TRANS,
        ETA,
        SPECULAR,
        SPEC_TINT,
        SHEEN,
        SHEEN_TINT,
        FLATNESS,
        CLEARCOAT,
        CLEARCOAT_GLOSS,
        DIFFUSE_RATE,
        SPECULAR_RATE,
        CLEARCOAT_RATE,
    ],
    nested: "",
    build: build_principled,
};

fn build_principled(obj: &Object, _: Nest) -> Result<Bsdf> {
    let index = if obj.has(ETA.name) {
        if obj.has(SPECULAR.name) {
            return Err(at_prop(
                obj,
                SPECULAR.name,
                format!(
                    "{}: give either \"eta\" or \"specular\", not both",
                    obj.describe()
                ),
            ));
        }
        PrincipledIndex::Eta(ETA.read_f32_or(obj, 1.5)?)
    } else {
        PrincipledIndex::Specular(SPECULAR.read_f32(obj)?)
    };
    let params = PrincipledParams {
        base_color: scalar_or_colour(obj, &BASE_COLOR)?,
        roughness: scalar_or_colour(obj, &ROUGHNESS)?,
        anisotropic: lobe(obj, &ANISOTROPIC)?,
        metallic: lobe(obj, &METALLIC)?,
        spec_trans: lobe(obj, &SPEC_TRANS)?,
        spec_tint: lobe(obj, &SPEC_TINT)?,
        sheen: lobe(obj, &SHEEN)?,
        sheen_tint: lobe(obj, &SHEEN_TINT)?,
        flatness: lobe(obj, &FLATNESS)?,
        clearcoat: lobe(obj, &CLEARCOAT)?,
        clearcoat_gloss: scalar_or_colour(obj, &CLEARCOAT_GLOSS)?,
        index,
        rates: SamplingRates {
            diffuse: DIFFUSE_RATE.read_f32(obj)?,
            specular: SPECULAR_RATE.read_f32(obj)?,
            clearcoat: CLEARCOAT_RATE.read_f32(obj)?,
        },
    };
    Ok(Bsdf::Principled(Principled::new(params)))
}

/// The texture parameter `p` (values in `[0, 1]`), its declared default when absent.
pub(super) fn scalar_or_colour(obj: &Object, p: &Param) -> Result<Texture> {
    let default = match p.default {
        Default::Float(v) => [v; 3],
        Default::Rgb(c) => c,
        other => unreachable!("\"{}\" has no constant default ({other:?})", p.name),
    };
    texture(obj, p.name, default, true)
}

/// A lobe's weight: `None` (the lobe is off) when the file does not give it or gives it as
/// the float 0, as Mitsuba 3 decides.
pub(super) fn lobe(obj: &Object, p: &Param) -> Result<Option<Texture>> {
    if !obj.has(p.name) {
        return Ok(None);
    }
    let t = scalar_or_colour(obj, p)?;
    Ok(switched_on(obj, p.name).then_some(t))
}

/// Whether a given lobe weight turns its lobe on: unless it is the float 0 (Mitsuba's
/// `get_flag`).
pub(super) fn switched_on(obj: &Object, name: &str) -> bool {
    !matches!(obj.prop(name), Some(q) if q.value == Value::Float(0.0))
}

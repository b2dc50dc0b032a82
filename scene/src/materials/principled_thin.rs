//! `principledthin` (Mitsuba 3): Burley's thin-sheet Disney BSDF. Names, defaults and lobe
//! switches as in Mitsuba 3.9.1 (a lobe whose weight is absent or the float 0 is off); the
//! parameters it shares with `principled` are declared in `principled.rs`.
use super::super::util::at_prop;
use super::principled::{
    lobe, scalar_or_colour, switched_on, weight, ANISOTROPIC, DIFFUSE_RATE, FLATNESS, ROUGHNESS,
    SHEEN_TINT, SPEC_TINT,
};
use super::texture::texture;
use super::{BsdfPlugin, Nest, Result};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, PrincipledThin, PrincipledThinParams, ThinSamplingRates};
use tessera_core::texture::Texture;

const BASE_COLOR: Param = Param::texture(
    "base_color",
    [0.5; 3],
    Range::Unit,
    "colour of the diffuse and transmitted light",
);
const SPEC_TRANS: Param = weight(
    "spec_trans",
    0.0,
    "weight of the specular lobes (reflection and transmission through the sheet)",
);
const SHEEN: Param = weight("sheen", 0.0, "weight of the grazing sheen (cloth)");
const DIFF_TRANS: Param = Param::new(
    "diff_trans",
    ParamType::Texture,
    Default::Float(0.0),
    Range::closed(0.0, 2.0),
    "diffuse transmission (half of it is the Lambertian transmission's weight)",
);
const ETA: Param = Param::new(
    "eta",
    ParamType::Texture,
    Default::Float(1.5),
    Range::Positive,
    "index of refraction of the sheet (sets the Fresnel term and the transmission's roughness)",
);
const SPEC_REFLECT_RATE: Param = Param::float(
    "specular_reflectance_sampling_rate",
    1.0,
    Range::NonNegative,
    "relative rate at which the specular reflection is sampled",
);
const SPEC_TRANS_RATE: Param = Param::float(
    "specular_transmittance_sampling_rate",
    1.0,
    Range::NonNegative,
    "relative rate at which the specular transmission is sampled",
);
const DIFF_TRANS_RATE: Param = Param::float(
    "diffuse_transmittance_sampling_rate",
    1.0,
    Range::NonNegative,
    "relative rate at which the diffuse transmission is sampled",
);

/// `principledthin`.
pub(crate) const PRINCIPLEDTHIN: BsdfPlugin = Plugin {
    name: "principledthin",
    aliases: &[],
    doc: "Burley's thin-sheet Disney BSDF as Mitsuba 3 writes it, for surfaces without volume \
          (leaves, paper, cloth, thin glass): diffuse with retro-reflection and sheen, GGX \
          reflection, rough transmission straight through the sheet, diffuse transmission; \
          both sides alike.",
    params: &[
        BASE_COLOR,
        ROUGHNESS,
        ANISOTROPIC,
        SPEC_TRANS,
        ETA,
        SPEC_TINT,
        SHEEN,
        SHEEN_TINT,
        FLATNESS,
        DIFF_TRANS,
        SPEC_REFLECT_RATE,
        SPEC_TRANS_RATE,
        DIFF_TRANS_RATE,
        DIFFUSE_RATE,
    ],
    nested: "",
    build: build_thin,
};

fn build_thin(obj: &Object, _: Nest) -> Result<Bsdf> {
    let eta = texture(obj, ETA.name, [1.5; 3], false)?;
    if let Texture::Constant(c) = &eta {
        if !(c.min_element() > 0.0) {
            return Err(ETA.out_of_range(obj, "positive", c.min_element()));
        }
    }
    let diff_trans = if obj.has(DIFF_TRANS.name) {
        let t = texture(obj, DIFF_TRANS.name, [0.0; 3], false)?;
        if !(t.max_value() <= 2.0) {
            return Err(at_prop(
                obj,
                DIFF_TRANS.name,
                format!(
                    "\"diff_trans\" of {} must be in [0, 2], found up to {}",
                    obj.describe(),
                    t.max_value()
                ),
            ));
        }
        switched_on(obj, DIFF_TRANS.name).then_some(t)
    } else {
        None
    };
    let params = PrincipledThinParams {
        base_color: scalar_or_colour(obj, &BASE_COLOR)?,
        roughness: scalar_or_colour(obj, &ROUGHNESS)?,
        anisotropic: lobe(obj, &ANISOTROPIC)?,
        spec_trans: lobe(obj, &SPEC_TRANS)?,
        spec_tint: lobe(obj, &SPEC_TINT)?,
        sheen: lobe(obj, &SHEEN)?,
        sheen_tint: lobe(obj, &SHEEN_TINT)?,
        flatness: lobe(obj, &FLATNESS)?,
        diff_trans,
        eta,
        rates: ThinSamplingRates {
            spec_reflect: SPEC_REFLECT_RATE.read_f32(obj)?,
            spec_trans: SPEC_TRANS_RATE.read_f32(obj)?,
            diffuse_reflect: DIFFUSE_RATE.read_f32(obj)?,
            diffuse_trans: DIFF_TRANS_RATE.read_f32(obj)?,
        },
    };
    Ok(Bsdf::PrincipledThin(PrincipledThin::new(params)))
}

//! `dielectric`, `roughdielectric`, `thindielectric` (Mitsuba 3 names and defaults). The models
//! use `eta = int_ior / ext_ior`, computed in single precision as Mitsuba does.
use super::super::util::at_prop;
use super::conductor::{
    textured_microfacet, ALPHA_TEXTURE, ALPHA_U_TEXTURE, ALPHA_V_TEXTURE, DISTRIBUTION,
    SAMPLE_VISIBLE, SPECULAR_REFLECTANCE,
};
use super::ior::{indices_differ, read_ior};
use super::texture::read_texture;
use super::{BsdfPlugin, Nest, Result};
use crate::plugin::{Param, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, Dielectric, RoughDielectric, ThinDielectric};
use tessera_core::texture::Texture;

/// `int_ior` of the glass plugins.
pub(crate) const INT_IOR: Param = Param::ior("int_ior", "bk7", "index of refraction inside");
/// `ext_ior` of the glass plugins.
pub(crate) const EXT_IOR: Param = Param::ior("ext_ior", "air", "index of refraction outside");
const SPECULAR_TRANSMITTANCE: Param = Param::texture(
    "specular_transmittance",
    [1.0; 3],
    Range::Unit,
    "factor on the transmission (not physical; for artistic control)",
);

/// `dielectric`.
pub(crate) const DIELECTRIC: BsdfPlugin = smooth_glass(
    "dielectric",
    "Smooth glass: Fresnel-weighted mirror reflection and refraction.",
    |obj, _| {
        let g = Glass::read(obj)?;
        Ok(Bsdf::Dielectric(Dielectric {
            eta: g.eta,
            specular_reflectance: g.reflectance,
            specular_transmittance: g.transmittance,
        }))
    },
);

/// `thindielectric`.
pub(crate) const THINDIELECTRIC: BsdfPlugin = smooth_glass(
    "thindielectric",
    "A thin glass sheet (a window pane): reflection and straight-through transmission, with the \
     inter-reflections inside the sheet summed.",
    |obj, _| {
        let g = Glass::read(obj)?;
        Ok(Bsdf::ThinDielectric(ThinDielectric {
            eta: g.eta,
            specular_reflectance: g.reflectance,
            specular_transmittance: g.transmittance,
        }))
    },
);

/// A smooth glass plugin: the indices and the two tints.
const fn smooth_glass(
    name: &'static str,
    doc: &'static str,
    build: fn(&Object, Nest) -> Result<Bsdf>,
) -> BsdfPlugin {
    Plugin {
        name,
        aliases: &[],
        doc,
        params: &[
            INT_IOR,
            EXT_IOR,
            SPECULAR_REFLECTANCE,
            SPECULAR_TRANSMITTANCE,
        ],
        nested: "",
        build,
    }
}

/// `roughdielectric`.
pub(crate) const ROUGHDIELECTRIC: BsdfPlugin = Plugin {
    name: "roughdielectric",
    aliases: &[],
    doc:
        "Rough glass (Walter et al. 2007): microfacet reflection and refraction. Its indices must \
          differ, as in Mitsuba 3.",
    params: &[
        INT_IOR,
        EXT_IOR,
        SPECULAR_REFLECTANCE,
        SPECULAR_TRANSMITTANCE,
        DISTRIBUTION,
        ALPHA_TEXTURE,
        ALPHA_U_TEXTURE,
        ALPHA_V_TEXTURE,
        SAMPLE_VISIBLE,
    ],
    nested: "",
    build: build_rough,
};

fn build_rough(obj: &Object, _: Nest) -> Result<Bsdf> {
    let g = Glass::read(obj)?;
    indices_differ(obj, g.int_ior, g.ext_ior)?;
    let (distribution, roughness) = textured_microfacet(obj)?;
    Ok(Bsdf::RoughDielectric(RoughDielectric {
        distribution,
        roughness,
        eta: g.eta,
        specular_reflectance: g.reflectance,
        specular_transmittance: g.transmittance,
    }))
}

/// What the three glass plugins share.
struct Glass {
    int_ior: f32,
    ext_ior: f32,
    eta: f32,
    reflectance: Texture,
    transmittance: Texture,
}

impl Glass {
    fn read(obj: &Object) -> Result<Glass> {
        let int_ior = read_ior(obj, &INT_IOR)? as f32;
        let ext_ior = read_ior(obj, &EXT_IOR)? as f32;
        let eta = int_ior / ext_ior;
        if !(eta.is_finite() && eta > 0.0) {
            return Err(at_prop(
                obj,
                "int_ior",
                format!(
                    "the indices of {} give no usable ratio ({int_ior} / {ext_ior})",
                    obj.describe()
                ),
            ));
        }
        Ok(Glass {
            int_ior,
            ext_ior,
            eta,
            reflectance: read_texture(obj, &SPECULAR_REFLECTANCE)?,
            transmittance: read_texture(obj, &SPECULAR_TRANSMITTANCE)?,
        })
    }
}

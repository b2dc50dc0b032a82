//! `plastic` and `roughplastic` (Mitsuba 3): a dielectric coating over a diffuse base. The
//! indices of `roughplastic` must differ, as Mitsuba 3 requires.
use super::super::util::at_prop;
use super::conductor::{
    read_distribution, ALPHA, DISTRIBUTION, SAMPLE_VISIBLE, SPECULAR_REFLECTANCE,
};
use super::ior::{indices_differ, read_eta};
use super::texture::read_texture;
use super::{BsdfPlugin, Nest, Result};
use crate::plugin::{Param, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, Plastic, RoughPlastic};
use tessera_core::texture::Texture;

/// `diffuse_reflectance` of the plastics.
pub(super) const DIFFUSE_REFLECTANCE: Param = Param::texture(
    "diffuse_reflectance",
    [0.5; 3],
    Range::Unit,
    "albedo of the diffuse base",
);
/// `int_ior` of the plastics.
pub(super) const INT_IOR: Param = Param::ior(
    "int_ior",
    "polypropylene",
    "index of refraction of the coating",
);
/// `ext_ior` of the plastics.
pub(super) const EXT_IOR: Param = Param::ior("ext_ior", "air", "index of refraction outside");
const NONLINEAR: Param = Param::boolean(
    "nonlinear",
    false,
    "account for the base's colour shift from internal scattering (Mitsuba 3's nonlinear)",
);
const ALPHA_U: Param = Param::float(
    "alpha_u",
    0.1,
    Range::Positive,
    "accepted instead of alpha when given with an equal alpha_v (the model is isotropic)",
);
const ALPHA_V: Param = Param::float(
    "alpha_v",
    0.1,
    Range::Positive,
    "accepted instead of alpha when given with an equal alpha_u (the model is isotropic)",
);

/// `plastic`.
pub(crate) const PLASTIC: BsdfPlugin = Plugin {
    name: "plastic",
    aliases: &[],
    doc: "A smooth dielectric coating over a diffuse base: varnished wood, smooth plastic.",
    params: &[
        DIFFUSE_REFLECTANCE,
        SPECULAR_REFLECTANCE,
        INT_IOR,
        EXT_IOR,
        NONLINEAR,
    ],
    nested: "",
    build: |obj, _| {
        let c = Coating::read(obj)?;
        Ok(Bsdf::Plastic(Plastic::new(
            c.diffuse,
            c.specular,
            c.eta,
            c.nonlinear,
        )))
    },
};

/// `roughplastic`.
pub(crate) const ROUGHPLASTIC: BsdfPlugin = Plugin {
    name: "roughplastic",
    aliases: &[],
    doc: "A rough dielectric coating (isotropic microfacets) over a diffuse base.",
    params: &[
        DIFFUSE_REFLECTANCE,
        SPECULAR_REFLECTANCE,
        INT_IOR,
        EXT_IOR,
        NONLINEAR,
        DISTRIBUTION,
        ALPHA,
        ALPHA_U,
        ALPHA_V,
        SAMPLE_VISIBLE,
    ],
    nested: "",
    build: build_rough,
};

fn build_rough(obj: &Object, _: Nest) -> Result<Bsdf> {
    let c = Coating::read(obj)?;
    indices_differ(obj, c.int_ior, c.ext_ior)?;
    let kind = read_distribution(obj)?;
    let alpha = roughness(obj)?;
    let sample_visible = SAMPLE_VISIBLE.read_bool(obj)?;
    Ok(Bsdf::RoughPlastic(RoughPlastic::new(
        c.diffuse,
        c.specular,
        kind,
        alpha,
        sample_visible,
        c.eta,
        c.nonlinear,
    )))
}

/// What both plugins read.
struct Coating {
    diffuse: Texture,
    specular: Texture,
    int_ior: f64,
    ext_ior: f64,
    eta: f32,
    nonlinear: bool,
}

impl Coating {
    fn read(obj: &Object) -> Result<Coating> {
        let diffuse = read_texture(obj, &DIFFUSE_REFLECTANCE)?;
        let specular = read_texture(obj, &SPECULAR_REFLECTANCE)?;
        let (int_ior, ext_ior, eta) = read_eta(obj, &INT_IOR, &EXT_IOR)?;
        let nonlinear = NONLINEAR.read_bool(obj)?;
        Ok(Coating {
            diffuse,
            specular,
            int_ior,
            ext_ior,
            eta,
            nonlinear,
        })
    }
}

/// The isotropic roughness: `alpha`, or equal `alpha_u` and `alpha_v`.
fn roughness(obj: &Object) -> Result<f32> {
    let (has_u, has_v) = (obj.has("alpha_u"), obj.has("alpha_v"));
    if !has_u && !has_v {
        return ALPHA.read_f32(obj);
    }
    if obj.has("alpha") {
        return Err(at_prop(
            obj,
            "alpha",
            format!(
                "{}: give either \"alpha\" or \"alpha_u\" / \"alpha_v\"",
                obj.describe()
            ),
        ));
    }
    let u = ALPHA_U.read_f32(obj)?;
    let v = ALPHA_V.read_f32(obj)?;
    if !(has_u && has_v) || u != v {
        let name = if has_u { "alpha_u" } else { "alpha_v" };
        return Err(at_prop(
            obj,
            name,
            format!(
                "{} is isotropic: \"alpha_u\" and \"alpha_v\" must both be given and equal \
                 (or use \"alpha\")",
                obj.describe()
            ),
        ));
    }
    Ok(u)
}

//! The BSDF family's table and its builder: the one file that knows every BSDF plugin.
use super::BsdfPlugin;
use super::{
    basic, chalmers, conductor, dielectric, maps, plastic, polarized, principled, principled_thin,
    wakame,
};
use crate::plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::bsdf::Bsdf;

/// Every `<bsdf type=...>` Tessera knows, in the order the reference lists them.
pub static BSDFS: &[BsdfPlugin] = &[
    basic::DIFFUSE,
    plastic::PLASTIC,
    plastic::ROUGHPLASTIC,
    polarized::PPLASTIC,
    conductor::CONDUCTOR,
    conductor::ROUGHCONDUCTOR,
    dielectric::DIELECTRIC,
    dielectric::ROUGHDIELECTRIC,
    dielectric::THINDIELECTRIC,
    principled::PRINCIPLED,
    principled_thin::PRINCIPLEDTHIN,
    basic::TWOSIDED,
    basic::BLENDBSDF,
    basic::MASK,
    basic::NULL,
    polarized::POLARIZER,
    maps::NORMALMAP_PLUGIN,
    maps::BUMPMAP_PLUGIN,
    wakame::MIRROR,
    wakame::MICROFACET,
    chalmers::BLINNPHONG,
    chalmers::BLINNPHONG_METAL,
];

/// Builds one BSDF (recursively for wrappers) and reports unused parameters.
pub(crate) fn build_bsdf(obj: &Object) -> Result<Bsdf> {
    let plugin = plugin::find(BSDFS, "bsdf", obj)?;
    let b = (plugin.build)(obj, build_bsdf)?;
    plugin.check_unused(obj)?;
    Ok(b)
}

//! Nori / Wakame BSDFs: `mirror` and Wakame's `microfacet`.
use super::dielectric::{EXT_IOR, INT_IOR};
use super::ior::read_eta;
use super::{BsdfPlugin, Nest, Result};
use crate::plugin::{Default, Param, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, Mirror, WakameMicrofacet};

/// `mirror`.
pub(crate) const MIRROR: BsdfPlugin = Plugin {
    name: "mirror",
    aliases: &[],
    doc: "Nori's perfect one-sided mirror.",
    params: &[],
    nested: "",
    build: |_, _| Ok(Bsdf::Mirror(Mirror {})),
};

const ALPHA: Param = Param::float("alpha", 0.1, Range::Positive, "Beckmann roughness");
const KD: Param = Param::rgb(
    "kd",
    Default::Rgb([0.5; 3]),
    Range::Unit,
    "albedo of the diffuse base",
);

/// `microfacet`.
pub(crate) const MICROFACET: BsdfPlugin = Plugin {
    name: "microfacet",
    aliases: &[],
    doc: "The Wakame assignment's Beckmann microfacet reflection over a diffuse base (Nori's \
          `intIOR` / `extIOR` are read as int_ior / ext_ior).",
    params: &[ALPHA, INT_IOR, EXT_IOR, KD],
    nested: "",
    build: build_microfacet,
};

fn build_microfacet(obj: &Object, _: Nest) -> Result<Bsdf> {
    let alpha = ALPHA.read_f32(obj)?;
    let (_, _, eta) = read_eta(obj, &INT_IOR, &EXT_IOR)?;
    let kd = KD.read_color(obj)?;
    Ok(Bsdf::WakameMicrofacet(WakameMicrofacet::new(
        alpha, eta, kd,
    )))
}

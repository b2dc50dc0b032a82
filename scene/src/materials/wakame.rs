//! Nori / Wakame BSDFs: `mirror` and Wakame's `microfacet`.
use super::super::util::at_prop;
use super::dielectric::{EXT_IOR, INT_IOR};
use super::ior::read_ior;
use super::{BsdfPlugin, Result};
use crate::plugin::{Default, Param, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, Mirror, WakameMicrofacet};

/// `mirror`.
pub const MIRROR: BsdfPlugin = Plugin {
    name: "mirror",
    aliases: &[],
    doc: "Nori's perfect one-sided mirror.",
    params: &[],
    nested: "",
    build: |_| Ok(Bsdf::Mirror(Mirror {})),
};

const ALPHA: Param = Param::float("alpha", 0.1, Range::Positive, "Beckmann roughness");
const KD: Param = Param::rgb(
    "kd",
    Default::Rgb([0.5; 3]),
    Range::Unit,
    "albedo of the diffuse base",
);

/// `microfacet`.
pub const MICROFACET: BsdfPlugin = Plugin {
    name: "microfacet",
    aliases: &[],
    doc: "The Wakame assignment's Beckmann microfacet reflection over a diffuse base (Nori's \
          `intIOR` / `extIOR` are read as int_ior / ext_ior).",
    params: &[ALPHA, INT_IOR, EXT_IOR, KD],
    nested: "",
    build: build_microfacet,
};

fn build_microfacet(obj: &Object) -> Result<Bsdf> {
    let alpha = ALPHA.read_f32(obj)?;
    let int_ior = read_ior(obj, &INT_IOR)?;
    let ext_ior = read_ior(obj, &EXT_IOR)?;
    let kd = KD.read_color(obj)?;
    let eta = (int_ior / ext_ior) as f32;
    if !(eta.is_finite() && eta > 0.0) {
        return Err(at_prop(
            obj,
            "int_ior",
            format!(
                "\"int_ior\" / \"ext_ior\" of {} is out of range",
                obj.describe()
            ),
        ));
    }
    Ok(Bsdf::WakameMicrofacet(WakameMicrofacet::new(
        alpha, eta, kd,
    )))
}

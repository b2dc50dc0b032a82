//! Chalmers' path-tracer tutorial materials: `blinnphong` and `blinnphong_metal` (its
//! `LinearBlend` is `blend`, built in `basic.rs`).
use super::super::util::at_prop;
use super::texture::read_texture;
use super::{nested_bsdfs, BsdfPlugin, Result};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{BlinnPhong, BlinnPhongMetal, Bsdf};

/// Default Blinn-Phong exponent.
pub(crate) const DEFAULT_SHININESS: f64 = 25.0;
/// Default Schlick reflectance at normal incidence (a dielectric of index 1.5).
pub(crate) const DEFAULT_R0: f64 = 0.04;

const SHININESS: Param = Param::float(
    "shininess",
    DEFAULT_SHININESS,
    Range::closed(0.0, 1e6),
    "Blinn-Phong exponent",
);
const R0: Param = Param::float(
    "r0",
    DEFAULT_R0,
    Range::Unit,
    "Schlick's reflectance at normal incidence",
);
const FRESNEL: Param = Param::new(
    "fresnel",
    ParamType::Float,
    Default::Note("r0's"),
    Range::Unit,
    "the tutorial's name for r0 (give one of the two)",
);
const COLOR: Param = Param::texture("color", [0.5; 3], Range::Unit, "the metal's tint");

/// `blinnphong`.
pub(crate) const BLINNPHONG: BsdfPlugin = Plugin {
    name: "blinnphong",
    aliases: &[],
    doc: "The Chalmers tutorial's dielectric layer: a Blinn-Phong lobe weighted by Schlick's \
          Fresnel over a nested model.",
    params: &[SHININESS, R0, FRESNEL],
    nested: "at most one `<bsdf>`: the layer below (none: nothing below)",
    build: |obj, nest| {
        let (shininess, r0) = lobe(obj)?;
        let base = nested_bsdfs(obj, 0, 1, nest)?.pop().map(Box::new);
        Ok(Bsdf::BlinnPhong(BlinnPhong::new(shininess, r0, base)))
    },
};

/// `blinnphong_metal`.
pub(crate) const BLINNPHONG_METAL: BsdfPlugin = Plugin {
    name: "blinnphong_metal",
    aliases: &[],
    doc: "The Chalmers tutorial's metal: a tinted Blinn-Phong lobe.",
    params: &[COLOR, SHININESS, R0, FRESNEL],
    nested: "",
    build: |obj, nest| {
        let (shininess, r0) = lobe(obj)?;
        nested_bsdfs(obj, 0, 0, nest)?;
        Ok(Bsdf::BlinnPhongMetal(BlinnPhongMetal::new(
            read_texture(obj, &COLOR)?,
            shininess,
            r0,
        )))
    },
};

/// The exponent and the reflectance at normal incidence (`r0` or its alias `fresnel`).
fn lobe(obj: &Object) -> Result<(f32, f32)> {
    let shininess = SHININESS.read_f32(obj)?;
    if obj.has("r0") && obj.has("fresnel") {
        return Err(at_prop(
            obj,
            "fresnel",
            format!(
                "{} takes \"r0\" or its alias \"fresnel\", not both",
                obj.describe()
            ),
        ));
    }
    let r0 = if obj.has("fresnel") {
        FRESNEL.read_f32_or(obj, DEFAULT_R0)?
    } else {
        R0.read_f32(obj)?
    };
    Ok((shininess, r0))
}

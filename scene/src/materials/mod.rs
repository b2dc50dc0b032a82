//! Builders from `<bsdf>` objects to core BSDFs, grouped by family; each file lists the
//! parameters of the plugins it builds (same names and defaults as Mitsuba 3 unless noted).
mod basic;
mod chalmers;
mod conductor;
mod dielectric;
pub(crate) mod ior;
mod plastic;
pub(crate) mod texture;
mod wakame;

use super::util::Result;
use crate::xml::{Child, Kind, Object};
use tessera_core::bsdf::Bsdf;

/// Every `<bsdf type=...>` Tessera knows.
pub const KNOWN: &[&str] = &[
    "diffuse",
    "twosided",
    "blendbsdf",
    "blend",
    "mask",
    "conductor",
    "roughconductor",
    "dielectric",
    "roughdielectric",
    "thindielectric",
    "plastic",
    "roughplastic",
    "mirror",
    "microfacet",
    "blinnphong",
    "blinnphong_metal",
];

/// Builds one BSDF (recursively for wrappers) and reports unused parameters.
pub fn build_bsdf(obj: &Object) -> Result<Bsdf> {
    let b = match obj.plugin.as_str() {
        "diffuse" | "twosided" | "blendbsdf" | "blend" | "mask" => basic::build(obj)?,
        "conductor" | "roughconductor" => conductor::build(obj)?,
        "dielectric" | "roughdielectric" | "thindielectric" => dielectric::build(obj)?,
        "plastic" | "roughplastic" => plastic::build(obj)?,
        "mirror" | "microfacet" => wakame::build(obj)?,
        "blinnphong" | "blinnphong_metal" => chalmers::build(obj)?,
        other => {
            return Err(obj.error(format!(
                "unknown bsdf \"{other}\" (known: {})",
                KNOWN.join(", ")
            )))
        }
    };
    obj.check_unused()?;
    Ok(b)
}

/// The nested `<bsdf>` children of `obj`, in document order.
pub fn nested(obj: &Object) -> Vec<&Child> {
    obj.children
        .iter()
        .filter(|c| c.obj.kind == Kind::Bsdf)
        .collect()
}

/// Builds the nested BSDFs of `obj`, which must number between `min` and `max`.
pub fn nested_bsdfs(obj: &Object, min: usize, max: usize) -> Result<Vec<Bsdf>> {
    let kids = nested(obj);
    if kids.len() < min || kids.len() > max {
        let want = if min == max {
            format!("{min}")
        } else {
            format!("{min} to {max}")
        };
        return Err(obj.error(format!(
            "{} needs {want} nested bsdf(s), found {}",
            obj.describe(),
            kids.len()
        )));
    }
    kids.iter()
        .map(|c| {
            c.mark_used();
            build_bsdf(&c.obj)
        })
        .collect()
}

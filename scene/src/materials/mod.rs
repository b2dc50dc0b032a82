//! The BSDF plugins: one [`Plugin`] per `<bsdf type=...>`, declared in the file of its family
//! (same names and defaults as Mitsuba 3 unless its declaration says otherwise), and the
//! table [`BSDFS`] that lists them.
mod basic;
mod chalmers;
mod conductor;
mod dielectric;
mod image_cache;
pub(crate) mod ior;
mod maps;
mod plastic;
mod principled;
mod principled_thin;
pub(crate) mod texture;
mod wakame;

use super::util::Result;
use crate::plugin::{self, Plugin};
use crate::xml::{Child, Kind, Object};
use tessera_core::bsdf::Bsdf;

/// A BSDF plugin.
pub type BsdfPlugin = Plugin<fn(&Object) -> Result<Bsdf>>;

/// Every `<bsdf type=...>` Tessera knows, in the order the reference lists them.
pub static BSDFS: &[BsdfPlugin] = &[
    basic::DIFFUSE,
    plastic::PLASTIC,
    plastic::ROUGHPLASTIC,
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
    maps::NORMALMAP_PLUGIN,
    wakame::MIRROR,
    wakame::MICROFACET,
    chalmers::BLINNPHONG,
    chalmers::BLINNPHONG_METAL,
];

/// Builds one BSDF (recursively for wrappers) and reports unused parameters.
pub fn build_bsdf(obj: &Object) -> Result<Bsdf> {
    let plugin = plugin::find(BSDFS, "bsdf", obj)?;
    let b = (plugin.build)(obj)?;
    plugin.check_unused(obj)?;
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

#[cfg(test)]
mod tests {
    use super::{build_bsdf, BSDFS};
    use crate::plugin::check::check_family;
    use crate::xml::Kind;

    #[test]
    fn declarations_match_what_the_builders_read() {
        check_family(
            BSDFS,
            Kind::Bsdf,
            build_bsdf,
            |name| {
                match name {
                    "twosided" | "mask" => "<bsdf type=\"diffuse\"/>",
                    "normalmap" => {
                        "<bsdf type=\"diffuse\"/><rgb name=\"normalmap\" value=\"0.6 0.4 0.9\"/>"
                    }
                    "blendbsdf" => "<bsdf type=\"diffuse\"/><bsdf type=\"conductor\"/>",
                    _ => "",
                }
                .to_string()
            },
            // Given alone, alpha_u (or alpha_v) asks for its partner.
            &[("roughplastic", "alpha_u"), ("roughplastic", "alpha_v")],
        );
    }
}

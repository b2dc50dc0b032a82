//! The BSDF plugins: one [`Plugin`] per `<bsdf type=...>`, declared in the file of its family
//! (same names and defaults as Mitsuba 3 unless its declaration says otherwise), and the
//! table `BSDFS` that lists them (in `table.rs`, above the plugins' files).
mod basic;
mod chalmers;
mod conductor;
mod dielectric;
mod image_cache;
pub(crate) mod ior;
mod maps;
mod mesh_attribute;
mod plastic;
mod polarized;
mod principled;
mod principled_thin;
mod raw_constant;
mod storage_format;
mod table;
pub(crate) mod texture;
mod texture_plugin;
mod wakame;

use super::util::Result;
use crate::plugin::Plugin;
use crate::xml::{Child, Kind, Object};
use tessera_core::bsdf::Bsdf;

pub(crate) use table::build_bsdf;
pub use table::BSDFS;

/// A BSDF plugin. Its builder gets the object and the builder of nested BSDFs (the family's
/// own, which the table passes down, so that a wrapper's file need not know the table).
pub(crate) type BsdfPlugin = Plugin<fn(&Object, Nest) -> Result<Bsdf>>;

/// Builds a nested `<bsdf>` (recursively, through the family's table).
pub(crate) type Nest = fn(&Object) -> Result<Bsdf>;

/// The nested `<bsdf>` children of `obj`, in document order.
pub fn nested(obj: &Object) -> Vec<&Child> {
    obj.children
        .iter()
        .filter(|c| c.obj.kind == Kind::Bsdf)
        .collect()
}

/// Builds the nested BSDFs of `obj`, which must number between `min` and `max`.
pub(crate) fn nested_bsdfs(obj: &Object, min: usize, max: usize, nest: Nest) -> Result<Vec<Bsdf>> {
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
            nest(&c.obj)
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
                if name == "bumpmap" {
                    return format!(
                        "<bsdf type=\"diffuse\"/><texture type=\"bitmap\"><string \
                         name=\"filename\" value=\"{}/../scenes/textures/tess_grey.png\"/>\
                         </texture>",
                        env!("CARGO_MANIFEST_DIR")
                    );
                }
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
            &[
                ("roughplastic", "alpha_u"),
                ("roughplastic", "alpha_v"),
                ("pplastic", "alpha_u"),
                ("pplastic", "alpha_v"),
            ],
        );
    }
}

//! `conductor` and `roughconductor` (Mitsuba 3 names and defaults), and the microfacet
//! parameters shared with `roughdielectric`.
//!
//! - `conductor`: `material` (string, default `"none"`: perfect mirror, `eta` 0, `k` 1) or
//!   `eta` / `k` (rgb / float, defaults 0 / 1; giving `eta` with a material other than `none`
//!   is an error, as in Mitsuba); `specular_reflectance` (rgb, default 1, in [0, 1]).
//! - `roughconductor`: the same plus `distribution` (`beckmann` (default) | `ggx`, any case),
//!   `alpha` (float, default 0.1) or both `alpha_u` and `alpha_v` (positive), `sample_visible`
//!   (boolean, default true).
//!
//! Named metals come from [`conductor_table`] (Mitsuba 3's RGB values). Roughness must be a
//! number here (Mitsuba also takes a texture).
use super::super::util::{at_prop, float_checked};
use super::texture::texture;
use super::Result;
use crate::xml::Object;
use tessera_core::bsdf::microfacet::{Microfacet, MicrofacetKind};
use tessera_core::bsdf::{Bsdf, Conductor, RoughConductor};
use tessera_core::texture::Texture;

#[path = "conductor_table.rs"]
pub(crate) mod conductor_table;

/// Builds the plugins of this file.
pub fn build(obj: &Object) -> Result<Bsdf> {
    let (eta, k) = complex_ior(obj)?;
    let specular_reflectance = texture(obj, "specular_reflectance", [1.0; 3], true)?;
    Ok(match obj.plugin.as_str() {
        "conductor" => Bsdf::Conductor(Conductor {
            eta,
            k,
            specular_reflectance,
        }),
        "roughconductor" => Bsdf::RoughConductor(RoughConductor {
            distribution: microfacet(obj)?,
            eta,
            k,
            specular_reflectance,
        }),
        other => return Err(obj.error(format!("bsdf \"{other}\" is not a conductor"))),
    })
}

/// `(eta, k)` from `material` or from `eta` / `k`, as Mitsuba 3 resolves them.
fn complex_ior(obj: &Object) -> Result<(Texture, Texture)> {
    let material = obj.string_opt("material")?;
    let named = material.as_deref().filter(|m| *m != "none");
    if obj.has("eta") || named.is_none() {
        if named.is_some() {
            return Err(at_prop(
                obj,
                "material",
                format!(
                    "{} takes either \"material\" or \"eta\"/\"k\", not both",
                    obj.describe()
                ),
            ));
        }
        let eta = texture(obj, "eta", [0.0; 3], false)?;
        let k = texture(obj, "k", [1.0; 3], false)?;
        return Ok((eta, k));
    }
    let name = named.unwrap_or_default();
    match conductor_table::lookup(name) {
        Some((eta, k)) => Ok((Texture::Constant(eta.into()), Texture::Constant(k.into()))),
        None => {
            let names: Vec<&str> = conductor_table::CONDUCTORS
                .iter()
                .map(|(n, _, _)| *n)
                .collect();
            Err(at_prop(
                obj,
                "material",
                format!(
                    "\"material\" of {}: unknown conductor \"{name}\" (known: none, {})",
                    obj.describe(),
                    names.join(", ")
                ),
            ))
        }
    }
}

/// The microfacet distribution of a rough plugin: `distribution`, `alpha` or
/// `alpha_u`/`alpha_v`, `sample_visible` (Mitsuba 3's names, defaults and rules).
pub(crate) fn microfacet(obj: &Object) -> Result<Microfacet> {
    let kind = match obj.string_opt("distribution")? {
        None => MicrofacetKind::Beckmann,
        Some(s) => match s.to_lowercase().as_str() {
            "beckmann" => MicrofacetKind::Beckmann,
            "ggx" => MicrofacetKind::Ggx,
            _ => {
                return Err(at_prop(
                    obj,
                    "distribution",
                    format!(
                        "\"distribution\" of {}: unknown distribution \"{s}\" (known: beckmann, \
                         ggx)",
                        obj.describe()
                    ),
                ))
            }
        },
    };
    let positive = |v: f64| v > 0.0;
    let (alpha_u, alpha_v) = if obj.has("alpha_u") || obj.has("alpha_v") {
        for (name, other) in [("alpha_u", "alpha_v"), ("alpha_v", "alpha_u")] {
            if !obj.has(name) {
                return Err(at_prop(
                    obj,
                    other,
                    format!(
                        "{} needs both \"alpha_u\" and \"alpha_v\" (or \"alpha\")",
                        obj.describe()
                    ),
                ));
            }
        }
        if obj.has("alpha") {
            return Err(at_prop(
                obj,
                "alpha",
                format!(
                    "{} takes either \"alpha\" or \"alpha_u\"/\"alpha_v\", not both",
                    obj.describe()
                ),
            ));
        }
        (
            float_checked(obj, "alpha_u", 0.1, positive, "positive")?,
            float_checked(obj, "alpha_v", 0.1, positive, "positive")?,
        )
    } else {
        let a = float_checked(obj, "alpha", 0.1, positive, "positive")?;
        (a, a)
    };
    Ok(Microfacet {
        kind,
        alpha_u,
        alpha_v,
        sample_visible: obj.boolean("sample_visible", true)?,
    })
}

//! `plastic` and `roughplastic` (Mitsuba 3): a dielectric coating over a diffuse base.
//!
//! - both: `diffuse_reflectance` (rgb or texture in [0, 1], default 0.5),
//!   `specular_reflectance` (rgb or texture in [0, 1], default 1), `int_ior` (float > 0 or
//!   material name, default "polypropylene" = 1.49), `ext_ior` (default "air" = 1.000277),
//!   `nonlinear` (bool, default false);
//! - `roughplastic` also: `distribution` (`beckmann` | `ggx`, default `beckmann`), `alpha`
//!   (float > 0, default 0.1; `alpha_u` and `alpha_v` are accepted only when equal, since the
//!   model is isotropic as in Mitsuba 3), `sample_visible` (bool, default true). The indices
//!   must differ, as Mitsuba 3 requires.
use super::super::util::{at_prop, float_checked};
use super::ior::ior;
use super::texture::texture;
use super::Result;
use crate::xml::Object;
use tessera_core::bsdf::microfacet::MicrofacetKind;
use tessera_core::bsdf::{Bsdf, Plastic, RoughPlastic};

/// Builds the plugins of this file.
pub fn build(obj: &Object) -> Result<Bsdf> {
    let diffuse = texture(obj, "diffuse_reflectance", [0.5; 3], true)?;
    let specular = texture(obj, "specular_reflectance", [1.0; 3], true)?;
    let int_ior = ior(obj, "int_ior", "polypropylene")?;
    let ext_ior = ior(obj, "ext_ior", "air")?;
    let nonlinear = obj.boolean("nonlinear", false)?;
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
    if obj.plugin == "plastic" {
        return Ok(Bsdf::Plastic(Plastic::new(
            diffuse, specular, eta, nonlinear,
        )));
    }
    if int_ior == ext_ior {
        return Err(at_prop(
            obj,
            "int_ior",
            format!(
                "\"int_ior\" and \"ext_ior\" of {} must differ (both are {int_ior})",
                obj.describe()
            ),
        ));
    }
    let kind = distribution(obj)?;
    let alpha = roughness(obj)?;
    let sample_visible = obj.boolean("sample_visible", true)?;
    Ok(Bsdf::RoughPlastic(RoughPlastic::new(
        diffuse,
        specular,
        kind,
        alpha,
        sample_visible,
        eta,
        nonlinear,
    )))
}

/// The `distribution` parameter (case-insensitive, as in Mitsuba 3).
fn distribution(obj: &Object) -> Result<MicrofacetKind> {
    let name = obj.string("distribution", "beckmann")?;
    match name.to_ascii_lowercase().as_str() {
        "beckmann" => Ok(MicrofacetKind::Beckmann),
        "ggx" => Ok(MicrofacetKind::Ggx),
        _ => Err(at_prop(
            obj,
            "distribution",
            format!(
                "\"distribution\" of {} must be \"beckmann\" or \"ggx\", found \"{name}\"",
                obj.describe()
            ),
        )),
    }
}

/// The isotropic roughness: `alpha`, or equal `alpha_u` and `alpha_v`.
fn roughness(obj: &Object) -> Result<f32> {
    let positive = |v: f64| v > 0.0;
    const WHAT: &str = "positive";
    let (has_u, has_v) = (obj.has("alpha_u"), obj.has("alpha_v"));
    if !has_u && !has_v {
        return float_checked(obj, "alpha", 0.1, positive, WHAT);
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
    let u = float_checked(obj, "alpha_u", 0.1, positive, WHAT)?;
    let v = float_checked(obj, "alpha_v", 0.1, positive, WHAT)?;
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

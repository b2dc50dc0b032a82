//! `dielectric`, `roughdielectric`, `thindielectric` (Mitsuba 3 names and defaults).
//!
//! - all three: `int_ior` (float or named material, default `"bk7"`), `ext_ior` (default
//!   `"air"`), both positive; the model uses `eta = int_ior / ext_ior` (computed in single
//!   precision, as Mitsuba does); `specular_reflectance`, `specular_transmittance` (rgb,
//!   default 1, in [0, 1]).
//! - `roughdielectric` also: `distribution`, `alpha` or `alpha_u`/`alpha_v`, `sample_visible`
//!   (see [`super::conductor::microfacet`]); its indices must differ (as in Mitsuba).
use super::super::util::at_prop;
use super::conductor::microfacet;
use super::ior::ior;
use super::texture::texture;
use super::Result;
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, Dielectric, RoughDielectric, ThinDielectric};

/// Builds the plugins of this file.
pub fn build(obj: &Object) -> Result<Bsdf> {
    let int_ior = ior(obj, "int_ior", "bk7")? as f32;
    let ext_ior = ior(obj, "ext_ior", "air")? as f32;
    let eta = int_ior / ext_ior;
    if !(eta.is_finite() && eta > 0.0) {
        return Err(at_prop(
            obj,
            "int_ior",
            format!(
                "the indices of {} give no usable ratio ({int_ior} / {ext_ior})",
                obj.describe()
            ),
        ));
    }
    let specular_reflectance = texture(obj, "specular_reflectance", [1.0; 3], true)?;
    let specular_transmittance = texture(obj, "specular_transmittance", [1.0; 3], true)?;
    Ok(match obj.plugin.as_str() {
        "dielectric" => Bsdf::Dielectric(Dielectric {
            eta,
            specular_reflectance,
            specular_transmittance,
        }),
        "thindielectric" => Bsdf::ThinDielectric(ThinDielectric {
            eta,
            specular_reflectance,
            specular_transmittance,
        }),
        "roughdielectric" => {
            if int_ior == ext_ior {
                return Err(at_prop(
                    obj,
                    "int_ior",
                    format!(
                        "{}: \"int_ior\" and \"ext_ior\" must differ (both {int_ior})",
                        obj.describe()
                    ),
                ));
            }
            Bsdf::RoughDielectric(RoughDielectric {
                distribution: microfacet(obj)?,
                eta,
                specular_reflectance,
                specular_transmittance,
            })
        }
        other => return Err(obj.error(format!("bsdf \"{other}\" is not a dielectric"))),
    })
}

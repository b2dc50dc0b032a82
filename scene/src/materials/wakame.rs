//! Nori / Wakame BSDFs.
//!
//! - `mirror`: no parameters (a perfect one-sided mirror).
//! - `microfacet`: `alpha` (float > 0, default 0.1), `int_ior` (Nori's `intIOR`; float > 0 or
//!   material name, default 1.5046), `ext_ior` (`extIOR`, default 1.000277), `kd` (rgb in
//!   [0, 1], default 0.5).
use super::super::util::{at_prop, color, float_checked};
use super::ior::ior;
use super::Result;
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, Mirror, WakameMicrofacet};

/// Builds the plugins of this file.
pub fn build(obj: &Object) -> Result<Bsdf> {
    if obj.plugin == "mirror" {
        return Ok(Bsdf::Mirror(Mirror {}));
    }
    let alpha = float_checked(obj, "alpha", 0.1, |v| v > 0.0, "positive")?;
    let int_ior = ior(obj, "int_ior", "bk7")?;
    let ext_ior = ior(obj, "ext_ior", "air")?;
    let kd = color(obj, "kd", [0.5; 3])?;
    if kd.max_element() > 1.0 {
        return Err(at_prop(
            obj,
            "kd",
            format!("\"kd\" of {} must be in [0, 1], found {kd}", obj.describe()),
        ));
    }
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

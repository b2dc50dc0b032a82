//! `diffuse`, `twosided`, `blendbsdf` (and Chalmers' `blend`), `mask`.
//!
//! - `diffuse`: `reflectance` (rgb or texture, default 0.5).
//! - `twosided`: one nested bsdf (both sides) or two (front, then back).
use super::texture::texture;
use super::{nested_bsdfs, Result};
use crate::xml::Object;
use tessera_core::bsdf::{Bsdf, Diffuse, TwoSided};

/// Builds the plugins of this file.
pub fn build(obj: &Object) -> Result<Bsdf> {
    Ok(match obj.plugin.as_str() {
        "diffuse" => Bsdf::Diffuse(Diffuse {
            reflectance: texture(obj, "reflectance", [0.5; 3], true)?,
        }),
        "twosided" => {
            let mut v = nested_bsdfs(obj, 1, 2)?;
            let back = v.pop().unwrap();
            let front = v.pop().unwrap_or_else(|| back.clone());
            Bsdf::TwoSided(TwoSided {
                front: Box::new(front),
                back: Box::new(back),
            })
        }
        other => return Err(obj.error(format!("bsdf \"{other}\" is not implemented yet"))),
    })
}

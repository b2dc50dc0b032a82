//! `diffuse`, `twosided`, `blendbsdf` (and Chalmers' `blend`), `mask`.
//!
//! - `diffuse`: `reflectance` (rgb or texture, default 0.5).
//! - `twosided`: one nested bsdf (both sides) or two (front, then back).
//! - `blendbsdf` / `blend`: `weight` (float or texture in [0, 1], default 0.5), exactly two
//!   nested bsdfs; `f = (1 - weight) first + weight second`.
//! - `mask`: `opacity` (float or texture in [0, 1], default 0.5), exactly one nested bsdf.
use super::texture::texture;
use super::{nested_bsdfs, Result};
use crate::xml::Object;
use tessera_core::bsdf::{Blend, Bsdf, Diffuse, Mask, TwoSided};

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
        "blendbsdf" | "blend" => {
            let weight = texture(obj, "weight", [0.5; 3], true)?;
            let mut v = nested_bsdfs(obj, 2, 2)?;
            let second = v.pop().unwrap();
            let first = v.pop().unwrap();
            Bsdf::Blend(Blend {
                weight,
                first: Box::new(first),
                second: Box::new(second),
            })
        }
        "mask" => {
            let opacity = texture(obj, "opacity", [0.5; 3], true)?;
            let nested = nested_bsdfs(obj, 1, 1)?.pop().unwrap();
            Bsdf::Mask(Mask {
                opacity,
                nested: Box::new(nested),
            })
        }
        other => return Err(obj.error(format!("bsdf \"{other}\" is not implemented yet"))),
    })
}

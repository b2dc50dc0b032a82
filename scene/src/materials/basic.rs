//! `diffuse`, `twosided`, `blendbsdf` (also Chalmers' `blend`) and `mask`: the plain reflector
//! and the wrappers that combine other BSDFs.
use super::texture::read_texture;
use super::{nested_bsdfs, BsdfPlugin, Nest, Result};
use crate::plugin::{Param, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::{Blend, Bsdf, Diffuse, Mask, TwoSided};

const REFLECTANCE: Param = Param::texture(
    "reflectance",
    [0.5; 3],
    Range::Unit,
    "albedo (diffuse reflectance)",
);

/// `diffuse`.
pub const DIFFUSE: BsdfPlugin = Plugin {
    name: "diffuse",
    aliases: &[],
    doc: "Lambertian reflection, one-sided (the back side is black unless wrapped in `twosided`).",
    params: &[REFLECTANCE],
    nested: "",
    build: |obj, _| {
        Ok(Bsdf::Diffuse(Diffuse {
            reflectance: read_texture(obj, &REFLECTANCE)?,
        }))
    },
};

/// `twosided`.
pub(crate) const TWOSIDED: BsdfPlugin = Plugin {
    name: "twosided",
    aliases: &[],
    doc: "Makes a one-sided model two-sided: the back is the front model seen from below, or a \
          second model.",
    params: &[],
    nested: "one `<bsdf>` for both sides, or two: the front, then the back",
    build: build_twosided,
};

fn build_twosided(obj: &Object, nest: Nest) -> Result<Bsdf> {
    let mut v = nested_bsdfs(obj, 1, 2, nest)?;
    let back = v.pop().expect("at least one nested bsdf");
    let front = v.pop().unwrap_or_else(|| back.clone());
    Ok(Bsdf::TwoSided(TwoSided {
        front: Box::new(front),
        back: Box::new(back),
    }))
}

const WEIGHT: Param = Param::texture(
    "weight",
    [0.5; 3],
    Range::Unit,
    "share of the second model: f = (1 - weight) first + weight second",
);

/// `blendbsdf` (Chalmers' `blend`).
pub(crate) const BLENDBSDF: BsdfPlugin = Plugin {
    name: "blendbsdf",
    aliases: &["blend"],
    doc: "A linear blend of two models.",
    params: &[WEIGHT],
    nested: "exactly two `<bsdf>`: the first and the second model",
    build: build_blend,
};

fn build_blend(obj: &Object, nest: Nest) -> Result<Bsdf> {
    let weight = read_texture(obj, &WEIGHT)?;
    let mut v = nested_bsdfs(obj, 2, 2, nest)?;
    let second = v.pop().expect("two nested bsdfs");
    let first = v.pop().expect("two nested bsdfs");
    Ok(Bsdf::Blend(Blend {
        weight,
        first: Box::new(first),
        second: Box::new(second),
    }))
}

const OPACITY: Param = Param::texture(
    "opacity",
    [0.5; 3],
    Range::Unit,
    "probability that a ray meets the nested model (else it passes straight through)",
);

/// `mask`.
pub(crate) const MASK: BsdfPlugin = Plugin {
    name: "mask",
    aliases: &[],
    doc: "An opacity mask over a model: cut-outs such as leaves.",
    params: &[OPACITY],
    nested: "exactly one `<bsdf>`",
    build: build_mask,
};

fn build_mask(obj: &Object, nest: Nest) -> Result<Bsdf> {
    let opacity = read_texture(obj, &OPACITY)?;
    let nested = nested_bsdfs(obj, 1, 1, nest)?
        .pop()
        .expect("one nested bsdf");
    Ok(Bsdf::Mask(Mask {
        opacity,
        nested: Box::new(nested),
    }))
}

/// `null`.
pub(crate) const NULL: BsdfPlugin = Plugin {
    name: "null",
    aliases: &[],
    doc: "A surface that does not interact with light: light crosses it unchanged. It bounds a \
          participating medium that its shape names as interior or exterior. `volpath` crosses \
          it without counting a bounce and its shadow rays pass through it, as in Mitsuba 3; \
          `path` follows it as a straight delta pass-through.",
    params: &[],
    nested: "",
    build: |_, _| Ok(Bsdf::Null(tessera_core::bsdf::Null)),
};

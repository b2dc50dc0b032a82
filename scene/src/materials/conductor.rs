//! `conductor` and `roughconductor` (Mitsuba 3 names and defaults), and the microfacet
//! parameters shared with `roughdielectric`. Named metals come from [`conductor_table`]
//! (Mitsuba 3's RGB values). `roughconductor` and `roughdielectric` take a texture for their
//! roughness, as Mitsuba 3 does.
use super::super::util::at_prop;
use super::texture::{read_texture, texture};
use super::{BsdfPlugin, Result};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::xml::Object;
use tessera_core::bsdf::microfacet::{Microfacet, MicrofacetKind};
use tessera_core::bsdf::roughness_texture::RoughnessTexture;
use tessera_core::bsdf::{Bsdf, Conductor, RoughConductor};
use tessera_core::texture::Texture;

#[path = "conductor_table.rs"]
pub(crate) mod conductor_table;

const MATERIAL: Param = Param::new(
    "material",
    ParamType::String,
    Default::Str("none"),
    Range::Note("a metal of Mitsuba 3's table, or none"),
    "named metal giving eta and k; \"none\" is a perfect mirror (eta 0, k 1)",
);
const ETA: Param = Param::texture(
    "eta",
    [0.0; 3],
    Range::NonNegative,
    "real part of the index of refraction (only with material \"none\")",
);
const K: Param = Param::texture(
    "k",
    [1.0; 3],
    Range::NonNegative,
    "imaginary part of the index of refraction (only with material \"none\")",
);
/// `specular_reflectance` of the metals and glasses (a tint).
pub(crate) const SPECULAR_REFLECTANCE: Param = Param::texture(
    "specular_reflectance",
    [1.0; 3],
    Range::Unit,
    "factor on the reflection (not physical; for artistic control)",
);
/// `distribution` of the rough plugins.
pub(crate) const DISTRIBUTION: Param = Param::new(
    "distribution",
    ParamType::Choice,
    Default::Str("beckmann"),
    Range::OneOfAnyCase(&["beckmann", "ggx"]),
    "microfacet distribution (any letter case)",
);
/// `alpha` of the rough plugins.
pub(crate) const ALPHA: Param = Param::float(
    "alpha",
    0.1,
    Range::Positive,
    "roughness (root mean square slope of the microfacets)",
);
/// `alpha_u` of the anisotropic rough plugins.
pub(crate) const ALPHA_U: Param = Param::new(
    "alpha_u",
    ParamType::Float,
    Default::Absent,
    Range::Positive,
    "roughness along the tangent; give alpha_u and alpha_v together, instead of alpha",
);
/// `alpha_v` of the anisotropic rough plugins.
pub(crate) const ALPHA_V: Param = Param::new(
    "alpha_v",
    ParamType::Float,
    Default::Absent,
    Range::Positive,
    "roughness along the bitangent; give alpha_u and alpha_v together, instead of alpha",
);
/// `alpha` of the rough plugins that take a texture for it (`roughconductor`,
/// `roughdielectric`).
pub(crate) const ALPHA_TEXTURE: Param = Param::new(
    "alpha",
    ParamType::Texture,
    Default::Float(0.1),
    Range::Positive,
    "roughness (root mean square slope of the microfacets); a texture is read as a scalar",
);
/// `alpha_u` of the rough plugins that take a texture for it.
pub(crate) const ALPHA_U_TEXTURE: Param = Param::new(
    "alpha_u",
    ParamType::Texture,
    Default::Absent,
    Range::Positive,
    "roughness along the tangent; give alpha_u and alpha_v together, instead of alpha",
);
/// `alpha_v` of the rough plugins that take a texture for it.
pub(crate) const ALPHA_V_TEXTURE: Param = Param::new(
    "alpha_v",
    ParamType::Texture,
    Default::Absent,
    Range::Positive,
    "roughness along the bitangent; give alpha_u and alpha_v together, instead of alpha",
);
/// `sample_visible` of the rough plugins.
pub(crate) const SAMPLE_VISIBLE: Param = Param::boolean(
    "sample_visible",
    true,
    "sample only the microfacet normals the incident direction sees (less noise)",
);

/// `conductor`.
pub(crate) const CONDUCTOR: BsdfPlugin = Plugin {
    name: "conductor",
    aliases: &[],
    doc: "A smooth metal: mirror reflection weighted by the complex Fresnel factor.",
    params: &[MATERIAL, ETA, K, SPECULAR_REFLECTANCE],
    nested: "",
    build: |obj, _| {
        let (eta, k) = complex_ior(obj)?;
        Ok(Bsdf::Conductor(Conductor {
            eta,
            k,
            specular_reflectance: read_texture(obj, &SPECULAR_REFLECTANCE)?,
        }))
    },
};

/// `roughconductor`.
pub(crate) const ROUGHCONDUCTOR: BsdfPlugin = Plugin {
    name: "roughconductor",
    aliases: &[],
    doc: "A rough metal: a microfacet model (Beckmann or GGX, isotropic or anisotropic) with \
          the complex Fresnel factor.",
    params: &[
        MATERIAL,
        ETA,
        K,
        SPECULAR_REFLECTANCE,
        DISTRIBUTION,
        ALPHA_TEXTURE,
        ALPHA_U_TEXTURE,
        ALPHA_V_TEXTURE,
        SAMPLE_VISIBLE,
    ],
    nested: "",
    build: |obj, _| {
        let (eta, k) = complex_ior(obj)?;
        let specular_reflectance = read_texture(obj, &SPECULAR_REFLECTANCE)?;
        let (distribution, roughness) = textured_microfacet(obj)?;
        Ok(Bsdf::RoughConductor(RoughConductor {
            distribution,
            roughness,
            eta,
            k,
            specular_reflectance,
        }))
    },
};

/// `(eta, k)` from `material` or from `eta` / `k`, as Mitsuba 3 resolves them.
fn complex_ior(obj: &Object) -> Result<(Texture, Texture)> {
    let material = MATERIAL.read_string(obj)?;
    let named = Some(material.as_str()).filter(|m| *m != "none");
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
        let eta = read_texture(obj, &ETA)?;
        let k = read_texture(obj, &K)?;
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

/// The `distribution` of a rough plugin.
pub(crate) fn read_distribution(obj: &Object) -> Result<MicrofacetKind> {
    Ok(match DISTRIBUTION.read_choice(obj)? {
        "ggx" => MicrofacetKind::Ggx,
        _ => MicrofacetKind::Beckmann,
    })
}

/// The microfacet distribution of `roughconductor` or `roughdielectric`, whose roughness may be
/// textures: [`microfacet`]'s rules, and a nested or referenced `<texture>` for `alpha`,
/// `alpha_u` or `alpha_v` (one constant over the surface is read as a number).
pub(crate) fn textured_microfacet(obj: &Object) -> Result<(Microfacet, Option<RoughnessTexture>)> {
    let is_texture = |name: &str| obj.has(name) && obj.prop(name).is_none();
    let names: &[&str] = if obj.has("alpha_u") || obj.has("alpha_v") {
        &["alpha_u", "alpha_v"]
    } else {
        &["alpha"]
    };
    let unpaired = names.len() == 2 && !(obj.has("alpha_u") && obj.has("alpha_v"));
    if unpaired || !names.iter().any(|n| is_texture(n)) {
        return Ok((microfacet(obj)?, None));
    }
    let mut tex = Vec::new();
    for &name in names {
        let t = if is_texture(name) {
            texture(obj, name, [0.1; 3], false)?
        } else {
            let p = match name {
                "alpha" => &ALPHA,
                "alpha_u" => &ALPHA_U,
                _ => &ALPHA_V,
            };
            let a = p.read_f32_opt(obj)?.ok_or_else(|| obj.missing(name))?;
            Texture::constant(a)
        };
        tex.push(t);
    }
    if names.len() == 2 && obj.has("alpha") {
        return Err(at_prop(
            obj,
            "alpha",
            format!(
                "{} takes either \"alpha\" or \"alpha_u\"/\"alpha_v\", not both",
                obj.describe()
            ),
        ));
    }
    let alpha_v = tex.pop().expect("one texture or two");
    let alpha_u = tex.pop().unwrap_or_else(|| alpha_v.clone());
    let placeholder = |t: &Texture| t.max_value().max(1e-4);
    let distribution = Microfacet {
        kind: read_distribution(obj)?,
        alpha_u: placeholder(&alpha_u),
        alpha_v: placeholder(&alpha_v),
        sample_visible: SAMPLE_VISIBLE.read_bool(obj)?,
    };
    Ok((distribution, Some(RoughnessTexture { alpha_u, alpha_v })))
}

/// The microfacet distribution of a rough plugin: `distribution`, `alpha` or
/// `alpha_u`/`alpha_v`, `sample_visible` (Mitsuba 3's names, defaults and rules).
pub(crate) fn microfacet(obj: &Object) -> Result<Microfacet> {
    let kind = read_distribution(obj)?;
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
        let read = |p: &Param| p.read_f32_opt(obj)?.ok_or_else(|| obj.missing(p.name));
        (read(&ALPHA_U)?, read(&ALPHA_V)?)
    } else {
        let a = ALPHA.read_f32(obj)?;
        (a, a)
    };
    Ok(Microfacet {
        kind,
        alpha_u,
        alpha_v,
        sample_visible: SAMPLE_VISIBLE.read_bool(obj)?,
    })
}

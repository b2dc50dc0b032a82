//! Tessera's reading of an MTL material: the Chalmers tutorial's material tree, built from the
//! MTL statements, plus an area light for `Ke`.
//!
//! Mapping (every value optional; defaults in brackets):
//! - `Kd` [0.5, Tessera's and Mitsuba's default diffuse] -> the diffuse colour `c`; `map_Kd`
//!   (PNG sRGB-decoded, EXR, PFM or `.hdr`; bilinear, repeat) -> a bitmap texture, multiplied
//!   by `Kd` when both are given (the MTL rule).
//! - `Ks` [0] -> the reflectivity `rho_s` = its largest component (the tutorial's
//!   `m_reflectivity`); `illum` 0 or 1 (no highlights) sets it to 0.
//! - `Ns` [25] -> the Blinn-Phong shininess; `Ni` -> the Schlick `r0 = ((Ni - 1)/(Ni + 1))^2`
//!   [0.04]; `Pm` (the PBR extension's metalness) [0] -> the metalness `m`.
//! - The tree of the tutorial's task 4:
//!   `blend(rho_s; diffuse(c), blend(m; blinnphong(Ns, r0; diffuse(c)), blinnphong_metal(c,
//!   Ns, r0)))`, where `blend(w; a, b) = (1 - w) a + w b`; a blend whose weight is 0 or 1 is
//!   left out.
//! - `d` (opacity) [1], or `1 - Tr` when there is no `d`, and `map_d` (read raw, as data; its
//!   luminance, times `d`) -> a `mask` around the tree when below 1 (cut-out transparency: light
//!   passes straight through, unrefracted).
//! - `Ke` -> an area emitter of that radiance on the material's faces when any component is
//!   positive (the faces keep the material's BSDF).
//!
//! Not mapped: `Ka` and `map_Ka` (ambient light has no meaning in a path tracer), refraction
//! (`illum` 4, 6, 7, 9, `Tf`: there is no MTL-to-glass mapping yet), `map_Ks`, `map_Ns`, bump
//! and normal maps; they are ignored.
use super::mtl::{At, MtlMaterial};
use crate::error::InputError;
use crate::materials::texture::{load_bitmap, BitmapSettings};
use tessera_core::bsdf::{Blend, BlinnPhong, BlinnPhongMetal, Bsdf, Diffuse, Mask};
use tessera_core::texture::{FilterType, Texture, UvTransform, WrapMode};
use tessera_core::Color;

/// Default shininess when `Ns` is absent.
const DEFAULT_NS: f32 = 25.0;
/// Default Schlick `r0` when `Ni` is absent (an index of 1.5).
const DEFAULT_R0: f32 = 0.04;

/// An MTL material as Tessera renders it.
#[derive(Clone, Debug)]
pub(crate) struct MtlBsdf {
    /// The surface model.
    pub bsdf: Bsdf,
    /// Radiance of an area light on the material's faces (`Ke`), if any.
    pub emission: Option<Color>,
}

/// A bitmap texture from a map statement, its pixels multiplied by `scale`.
fn map_texture(
    map: &At<std::path::PathBuf>,
    raw: bool,
    scale: Color,
) -> Result<Texture, InputError> {
    let settings = BitmapSettings {
        raw,
        unit: true,
        filter: FilterType::Bilinear,
        wrap: WrapMode::Repeat,
        to_uv: UvTransform::IDENTITY,
        scale,
        half: false,
    };
    let name = map.value.display().to_string();
    let bitmap =
        load_bitmap(&map.value, &name, settings).map_err(|e| InputError::at(&map.loc, e))?;
    Ok(Texture::Bitmap(bitmap))
}

fn blend(w: f32, first: Bsdf, second: Bsdf) -> Bsdf {
    if w <= 0.0 {
        first
    } else if w >= 1.0 {
        second
    } else {
        Bsdf::Blend(Blend {
            weight: Texture::constant(w),
            first: Box::new(first),
            second: Box::new(second),
        })
    }
}

/// Builds the material `m` of an MTL library (texture files relative to it were resolved by
/// the parser). Errors (an unreadable texture) are located at the statement.
pub(crate) fn mtl_bsdf(m: &MtlMaterial) -> Result<MtlBsdf, InputError> {
    let kd =
        m.kd.as_ref()
            .map_or(Color::splat(0.5), |k| Color::from(k.value));
    let color = match &m.map_kd {
        Some(map) => map_texture(
            map,
            false,
            m.kd.as_ref().map_or(Color::ONE, |k| Color::from(k.value)),
        )?,
        None => Texture::Constant(kd),
    };
    let specular = !matches!(m.illum.as_ref().map(|i| i.value), Some(0 | 1));
    let rho_s = match (&m.ks, specular) {
        (Some(ks), true) => ks.value.iter().fold(0.0f32, |a, &b| a.max(b)),
        _ => 0.0,
    };
    let ns = m.ns.as_ref().map_or(DEFAULT_NS, |v| v.value);
    let r0 = m.ni.as_ref().map_or(DEFAULT_R0, |n| {
        let r = (n.value - 1.0) / (n.value + 1.0);
        r * r
    });
    let metalness = m.pm.as_ref().map_or(0.0, |v| v.value);
    let diffuse = Bsdf::Diffuse(Diffuse {
        reflectance: color.clone(),
    });
    let mut bsdf = if rho_s > 0.0 {
        let dielectric = Bsdf::BlinnPhong(BlinnPhong::new(ns, r0, Some(Box::new(diffuse.clone()))));
        let metal = Bsdf::BlinnPhongMetal(BlinnPhongMetal::new(color, ns, r0));
        blend(rho_s, diffuse, blend(metalness, dielectric, metal))
    } else {
        diffuse
    };
    let d = match (&m.d, &m.tr) {
        (Some(d), _) => d.value,
        (None, Some(tr)) => 1.0 - tr.value,
        (None, None) => 1.0,
    };
    let opacity = match &m.map_d {
        Some(map) => Some(map_texture(map, true, Color::splat(d))?),
        None if d < 1.0 => Some(Texture::constant(d)),
        None => None,
    };
    if let Some(opacity) = opacity {
        bsdf = Bsdf::Mask(Mask {
            opacity,
            nested: Box::new(bsdf),
        });
    }
    let emission =
        m.ke.as_ref()
            .map(|k| Color::from(k.value))
            .filter(|c| c.max_element() > 0.0);
    Ok(MtlBsdf { bsdf, emission })
}

//! Texture-valued parameters: a constant (`<rgb>` or `<float>`) or a `<texture>` (nested with
//! the parameter's name, or a `<ref name=... id=...>` to one declared elsewhere).
//!
//! - `bitmap`: `filename` (string, required: PNG, EXR, PFM or RGBE `.hdr`, relative to the
//!   scene file; a PNG's alpha channel is ignored), `raw` (boolean, default false: when false a
//!   PNG is sRGB-decoded to linear values, as Mitsuba 3 does), `filter_type` (`bilinear` |
//!   `nearest`, default bilinear), `wrap_mode` (`repeat` | `mirror` | `clamp`, default repeat),
//!   `to_uv` (transform, default identity), `accel` (boolean, accepted and ignored: a Mitsuba
//!   GPU option). Every pixel must be finite and non-negative, and in [0, 1] where the
//!   parameter is a reflectance or weight.
//! - `checkerboard`: `color0` (rgb or texture, default 0.4), `color1` (rgb or texture, default
//!   0.2), `to_uv` (transform, default identity).
//!
//! The conventions (which row is `v = 0`, pixel centres, wrapping) are in
//! `tessera_core::texture`'s plugin files.
use super::super::util::{at_prop, Result};
use crate::image::read_image;
use crate::plugin::{Default, Param, Range};
use crate::xml::{Kind, Object};
use glam::{DMat4, Vec3};
use std::path::Path;
use tessera_core::texture::{Bitmap, Checkerboard, FilterType, Texture, UvTransform, WrapMode};

/// The declared texture parameter `p` of `obj`: its default colour when absent; every value
/// in `[0, 1]` when its range is [`Range::Unit`], else only non-negative.
pub fn read_texture(obj: &Object, p: &Param) -> Result<Texture> {
    let Default::Rgb(default) = p.default else {
        unreachable!("texture \"{}\" has no constant default", p.name)
    };
    texture(obj, p.name, default, p.range == Range::Unit)
}

/// The texture parameter `name` of `obj` (constant `default` when absent). With `unit`, every
/// value must lie in `[0, 1]` (reflectances, weights); otherwise only non-negative.
pub fn texture(obj: &Object, name: &str, default: [f64; 3], unit: bool) -> Result<Texture> {
    if obj.has(name) && obj.prop(name).is_none() {
        let child = obj.child(name).expect("a named child exists");
        if child.obj.kind != Kind::Texture {
            return Err(crate::error::InputError::at(
                &child.loc,
                format!(
                    "parameter \"{name}\" of {} must be a texture or a value, found {}",
                    obj.describe(),
                    child.obj.describe()
                ),
            ));
        }
        return build_texture(&child.obj, unit);
    }
    let c = obj.rgb(name, default)?;
    let v = Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32);
    let ok = v.is_finite() && v.min_element() >= 0.0 && (!unit || v.max_element() <= 1.0);
    if !ok {
        return Err(at_prop(
            obj,
            name,
            format!("\"{name}\" of {} must be {}", obj.describe(), range(unit)),
        ));
    }
    Ok(Texture::Constant(v))
}

fn range(unit: bool) -> &'static str {
    if unit {
        "in [0, 1]"
    } else {
        "finite and non-negative"
    }
}

/// Builds a `<texture>` object and reports its unused parameters.
fn build_texture(obj: &Object, unit: bool) -> Result<Texture> {
    let t = match obj.plugin.as_str() {
        "bitmap" => Texture::Bitmap(bitmap(obj, unit)?),
        "checkerboard" => Texture::Checkerboard(Checkerboard {
            color0: Box::new(texture(obj, "color0", [0.4; 3], unit)?),
            color1: Box::new(texture(obj, "color1", [0.2; 3], unit)?),
            to_uv: to_uv(obj)?,
        }),
        other => {
            return Err(obj.error(format!(
                "unknown texture \"{other}\" (known: bitmap, checkerboard)"
            )))
        }
    };
    obj.check_unused()?;
    Ok(t)
}

/// The `to_uv` transform: rows and columns 0, 1 and 3 of the 4x4 matrix, as Mitsuba 3 reads it.
fn to_uv(obj: &Object) -> Result<UvTransform> {
    let m: DMat4 = obj.transform("to_uv", DMat4::IDENTITY)?;
    let row = |r: usize| [m.col(0)[r] as f32, m.col(1)[r] as f32, m.col(3)[r] as f32];
    let t = UvTransform {
        row_u: row(0),
        row_v: row(1),
    };
    if t.row_u.iter().chain(&t.row_v).any(|v| !v.is_finite()) {
        return Err(at_prop(
            obj,
            "to_uv",
            format!("\"to_uv\" of {} is out of range", obj.describe()),
        ));
    }
    Ok(t)
}

/// The sRGB decoding of a value in [0, 1] (IEC 61966-2-1).
fn srgb_to_linear(v: f32) -> f32 {
    let v = f64::from(v);
    let l = if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    };
    l as f32
}

fn bitmap(obj: &Object, unit: bool) -> Result<Bitmap> {
    let name = obj
        .string_opt("filename")?
        .ok_or_else(|| obj.missing("filename"))?;
    let raw = obj.boolean("raw", false)?;
    let filter = match obj.string("filter_type", "bilinear")?.as_str() {
        "bilinear" => FilterType::Bilinear,
        "nearest" => FilterType::Nearest,
        other => {
            return Err(at_prop(
                obj,
                "filter_type",
                format!("unknown filter_type \"{other}\" (bilinear, nearest)"),
            ))
        }
    };
    let wrap = match obj.string("wrap_mode", "repeat")?.as_str() {
        "repeat" => WrapMode::Repeat,
        "mirror" => WrapMode::Mirror,
        "clamp" => WrapMode::Clamp,
        other => {
            return Err(at_prop(
                obj,
                "wrap_mode",
                format!("unknown wrap_mode \"{other}\" (repeat, mirror, clamp)"),
            ))
        }
    };
    let to_uv = to_uv(obj)?;
    obj.boolean("accel", true)?;
    let base = obj
        .loc
        .file
        .parent()
        .map(|p| p.to_path_buf())
        .unwrap_or_default();
    let settings = BitmapSettings {
        raw,
        unit,
        filter,
        wrap,
        to_uv,
        scale: Vec3::ONE,
    };
    load_bitmap(&base.join(&name), &name, settings).map_err(|msg| at_prop(obj, "filename", msg))
}

/// How to read and look up an image texture.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BitmapSettings {
    /// Keep PNG values as stored (no sRGB decoding).
    pub raw: bool,
    /// Require values in [0, 1].
    pub unit: bool,
    /// Reconstruction filter.
    pub filter: FilterType,
    /// Wrap mode.
    pub wrap: WrapMode,
    /// Map applied to uv.
    pub to_uv: UvTransform,
    /// Factor applied to every pixel (after sRGB decoding).
    pub scale: Vec3,
}

/// Reads the image at `path` (named `name` in messages) as a bitmap texture; the message of an
/// error names the file and the problem.
pub(crate) fn load_bitmap(
    path: &Path,
    name: &str,
    s: BitmapSettings,
) -> std::result::Result<Bitmap, String> {
    let img = read_image(path)?;
    let png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let decode = png && !s.raw;
    let mut pixels = Vec::with_capacity(img.data.len());
    for (i, p) in img.data.iter().enumerate() {
        let mut c = Vec3::from(*p);
        if decode {
            c = Vec3::new(
                srgb_to_linear(c.x),
                srgb_to_linear(c.y),
                srgb_to_linear(c.z),
            );
        }
        c *= s.scale;
        if !(c.is_finite() && c.min_element() >= 0.0 && (!s.unit || c.max_element() <= 1.0)) {
            let (x, y) = (i % img.width as usize, i / img.width as usize);
            return Err(format!(
                "\"{name}\": pixel ({x}, {y}) is {:?}; values of this parameter must be {}",
                c.to_array(),
                range(s.unit)
            ));
        }
        pixels.push(c);
    }
    let (w, h) = (img.width as usize, img.height as usize);
    Bitmap::new(w, h, pixels, s.filter, s.wrap, s.to_uv)
        .ok_or_else(|| format!("\"{name}\": unusable image size {w}x{h}"))
}

//! Texture-valued parameters: a constant (`<rgb>` or `<float>`) or a `<texture>` (nested with
//! the parameter's name, or a `<ref name=... id=...>` to one declared elsewhere), and the
//! texture plugins `bitmap`, `checkerboard`, `mesh_attribute` and `rawconstant` ([`TEXTURES`]). Every value must be finite and
//! non-negative, and in [0, 1] where the parameter is a reflectance or weight. The conventions
//! (which row is `v = 0`, pixel centres, wrapping) are in `tessera_core::texture`'s plugin files.
use super::super::util::{at_prop, Result};
use super::image_cache::shared_pixels;
use super::mesh_attribute::MESH_ATTRIBUTE;
use super::raw_constant::RAW_CONSTANT;
use super::storage_format::{round_to_half, Storage, FORMAT};
use super::texture_plugin::TexturePlugin;
use crate::image::{is_srgb_coded, read_texture_image, TextureImage};
use crate::plugin::{self, Default, Param, Plugin, Range};
use crate::xml::{Kind, Object};
use glam::{DMat4, Vec3};
use std::path::Path;
use std::sync::Arc;
use tessera_core::texture::{
    Bitmap, Checkerboard, CodeTable, FilterType, Texels, Texture, UvTransform, WrapMode,
};

/// The declared texture parameter `p` of `obj`: its default colour when absent; every value
/// in `[0, 1]` when its range is [`Range::Unit`], else only non-negative.
pub(crate) fn read_texture(obj: &Object, p: &Param) -> Result<Texture> {
    texture(obj, p.name, rgb_default(p), p.range == Range::Unit)
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
        let t = build_texture(&child.obj, unit)?;
        if t.reads_mesh() && obj.kind != Kind::Bsdf {
            // Only a BSDF's lookups are given the triangle hit.
            return Err(crate::error::InputError::at(
                &child.loc,
                format!(
                    "a mesh_attribute texture as \"{name}\" of {}: only BSDF parameters can \
                     read mesh attributes",
                    obj.describe()
                ),
            ));
        }
        return Ok(t);
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

/// Every `<texture type=...>` Tessera knows.
pub static TEXTURES: &[TexturePlugin] = &[BITMAP, CHECKERBOARD, MESH_ATTRIBUTE, RAW_CONSTANT];

/// Builds a `<texture>` object and reports its unused parameters.
pub(crate) fn build_texture(obj: &Object, unit: bool) -> Result<Texture> {
    let plugin = plugin::find(TEXTURES, "texture", obj)?;
    let t = (plugin.build)(obj, unit)?;
    plugin.check_unused(obj)?;
    Ok(t)
}

const UNIT_RULE: Range = Range::Note("in [0, 1] for a reflectance or weight, else non-negative");
const COLOR0: Param = Param::texture("color0", [0.4; 3], UNIT_RULE, "colour of the even squares");
const COLOR1: Param = Param::texture("color1", [0.2; 3], UNIT_RULE, "colour of the odd squares");
const TO_UV: Param = Param::transform(
    "to_uv",
    "map applied to the surface's uv before the lookup (rows and columns 0, 1 and 3 of the 4x4)",
);

/// `checkerboard`.
pub(crate) const CHECKERBOARD: TexturePlugin = Plugin {
    name: "checkerboard",
    aliases: &[],
    doc: "Two colours in a checkerboard of 2x2 squares over the unit uv square.",
    params: &[COLOR0, COLOR1, TO_UV],
    nested: "",
    build: |obj, unit| {
        Ok(Texture::Checkerboard(Checkerboard {
            color0: Box::new(texture(obj, COLOR0.name, rgb_default(&COLOR0), unit)?),
            color1: Box::new(texture(obj, COLOR1.name, rgb_default(&COLOR1), unit)?),
            to_uv: to_uv(obj)?,
        }))
    },
};

const FILENAME: Param = Param::file(
    "a PNG, JPEG, BMP, TGA, EXR, PFM or RGBE .hdr file, relative to the scene file",
    "the image (an alpha channel is ignored)",
);
const RAW: Param = Param::boolean(
    "raw",
    false,
    "keep an 8-bit image's (PNG, JPEG, BMP, TGA) values as they are; when false they are \
     sRGB-decoded to linear values",
);
const FILTER_TYPE: Param = Param::choice(
    "filter_type",
    "bilinear",
    &["bilinear", "nearest"],
    "reconstruction between pixels",
);
const WRAP_MODE: Param = Param::choice(
    "wrap_mode",
    "repeat",
    &["repeat", "mirror", "clamp"],
    "what uv outside [0, 1] reads",
);
const ACCEL: Param =
    Param::boolean("accel", true, "Mitsuba's GPU lookup option; has no effect").ignored();

/// `bitmap`.
pub(crate) const BITMAP: TexturePlugin = Plugin {
    name: "bitmap",
    aliases: &[],
    doc: "An image texture.",
    params: &[FILENAME, RAW, FILTER_TYPE, WRAP_MODE, TO_UV, ACCEL, FORMAT],
    nested: "",
    build: |obj, unit| Ok(Texture::Bitmap(bitmap(obj, unit)?)),
};

fn rgb_default(p: &Param) -> [f64; 3] {
    match p.default {
        Default::Rgb(c) => c,
        other => unreachable!("texture \"{}\" has no colour default ({other:?})", p.name),
    }
}

/// The `to_uv` transform: rows and columns 0, 1 and 3 of the 4x4 matrix, as Mitsuba 3 reads it.
fn to_uv(obj: &Object) -> Result<UvTransform> {
    let m: DMat4 = obj.transform(TO_UV.name, DMat4::IDENTITY)?;
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
    let name = FILENAME.read_string(obj)?;
    let raw = RAW.read_bool(obj)?;
    let filter = match FILTER_TYPE.read_choice(obj)? {
        "nearest" => FilterType::Nearest,
        _ => FilterType::Bilinear,
    };
    let wrap = match WRAP_MODE.read_choice(obj)? {
        "mirror" => WrapMode::Mirror,
        "clamp" => WrapMode::Clamp,
        _ => WrapMode::Repeat,
    };
    let to_uv = to_uv(obj)?;
    ACCEL.read_bool(obj)?;
    let storage = Storage::of(FORMAT.read_choice(obj)?);
    if storage == Storage::Byte && !is_srgb_coded(&obj.resolve_file(&name)) {
        return Err(at_prop(
            obj,
            FORMAT.name,
            format!(
                "format \"uint8\" of {} on the floating-point image \"{name}\": Tessera does \
                 not quantize such images to 8 bits as Mitsuba 3 does (use \"auto\" or \
                 \"variant\")",
                obj.describe()
            ),
        ));
    }
    let settings = BitmapSettings {
        raw,
        unit,
        filter,
        wrap,
        to_uv,
        scale: Vec3::ONE,
        half: storage == Storage::Half,
    };
    load_bitmap(&obj.resolve_file(&name), &name, settings)
        .map_err(|msg| at_prop(obj, "filename", msg))
}

/// How to read and look up an image texture.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BitmapSettings {
    /// Keep 8-bit values as stored (no sRGB decoding).
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
    /// Round every value to half precision (`format="float16"`), after decoding and scaling.
    pub half: bool,
}

/// Reads the image at `path` (named `name` in messages) as a bitmap texture; the message of an
/// error names the file and the problem.
pub(crate) fn load_bitmap(
    path: &Path,
    name: &str,
    s: BitmapSettings,
) -> std::result::Result<Bitmap, String> {
    let (w, h, pixels) = shared_pixels(path, s.raw, s.unit, s.scale, || decode(path, name, &s))?;
    let pixels = match (s.half, pixels) {
        (false, p) => p,
        (true, Texels::Float(p)) => Texels::Float(p.iter().map(|&c| round_to_half(c)).collect()),
        (true, Texels::Codes(c, t)) => {
            let rounded: [Vec3; 256] =
                std::array::from_fn(|k| round_to_half(Vec3::new(t[0][k], t[1][k], t[2][k])));
            let t = std::array::from_fn(|ch| std::array::from_fn(|k| rounded[k][ch]));
            Texels::Codes(c, Arc::new(t))
        }
    };
    Bitmap::new(w, h, pixels, s.filter, s.wrap, s.to_uv)
        .ok_or_else(|| format!("\"{name}\": unusable image size {w}x{h}"))
}

/// The pixels of the image at `path`, decoded (sRGB unless raw, scaled) and checked. An 8-bit
/// image keeps its codes, each channel's 256 values worked out once (the values of decoding
/// `code / 255` as a float image is).
fn decode(
    path: &Path,
    name: &str,
    s: &BitmapSettings,
) -> std::result::Result<(usize, usize, Texels), String> {
    let srgb = is_srgb_coded(path) && !s.raw;
    let (width, height, pixels) = match read_texture_image(path)? {
        TextureImage::Codes {
            width,
            height,
            data,
        } => {
            let value = |ch: usize, k: usize| {
                let v = k as f32 / 255.0;
                (if srgb { srgb_to_linear(v) } else { v }) * s.scale[ch]
            };
            let table: CodeTable = std::array::from_fn(|ch| std::array::from_fn(|k| value(ch, k)));
            (width, height, Texels::Codes(data.into(), Arc::new(table)))
        }
        TextureImage::Float(img) => {
            let pixel = |p: &[f32; 3]| {
                let c = Vec3::from(*p);
                let c = if srgb {
                    Vec3::new(
                        srgb_to_linear(c.x),
                        srgb_to_linear(c.y),
                        srgb_to_linear(c.z),
                    )
                } else {
                    c
                };
                c * s.scale
            };
            let pixels: Arc<[Vec3]> = img.data.iter().map(pixel).collect();
            (img.width, img.height, Texels::Float(pixels))
        }
    };
    check_pixels(name, s.unit, width, &pixels)?;
    Ok((width as usize, height as usize, pixels))
}

/// Checks that every pixel is finite, not negative, and at most 1 when `unit`; the error names
/// the first pixel that is not. For codes, only the table is checked unless one of its values
/// is out of range.
fn check_pixels(
    name: &str,
    unit: bool,
    width: u32,
    pixels: &Texels,
) -> std::result::Result<(), String> {
    let bad =
        |c: &Vec3| !(c.is_finite() && c.min_element() >= 0.0 && (!unit || c.max_element() <= 1.0));
    if let Texels::Codes(_, t) = pixels {
        // The check is per channel value: a table of good values makes only good pixels.
        if t.iter().flatten().all(|&v| !bad(&Vec3::splat(v))) {
            return Ok(());
        }
    }
    if let Some(i) = pixels.iter().position(|c| bad(&c)) {
        let (x, y) = (i % width as usize, i / width as usize);
        return Err(format!(
            "\"{name}\": pixel ({x}, {y}) is {:?}; values of this parameter must be {}",
            pixels.get(i).to_array(),
            range(unit)
        ));
    }
    Ok(())
}

#[cfg(test)]
mod declaration_tests {
    use super::{build_texture, TEXTURES};
    use crate::plugin::check::check_family;
    use crate::xml::Kind;

    #[test]
    fn declarations_match_what_the_builders_read() {
        let image = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/textures/tiles.png");
        for unit in [false, true] {
            check_family(
                TEXTURES,
                Kind::Texture,
                |obj| build_texture(obj, unit),
                |name| match name {
                    "bitmap" => format!("<string name=\"filename\" value=\"{image}\"/>"),
                    "mesh_attribute" => "<string name=\"name\" value=\"vertex_color\"/>".into(),
                    "rawconstant" => "<vector name=\"value\" value=\"0.5, 0.5, 1\"/>".into(),
                    _ => String::new(),
                },
                &[],
            );
        }
    }
}

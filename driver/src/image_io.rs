//! Reading and writing images: EXR and PFM (linear float RGB), PNG (8-bit sRGB, clamped).
//!
//! Writes are atomic: the image goes to a temporary file beside the target, which is then renamed
//! over it, so a reader never sees half a file and a failed write leaves the old file intact.
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

/// A linear RGB float image, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels.
    pub data: Vec<[f32; 3]>,
}

/// Output formats, chosen by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// OpenEXR, 32-bit float RGB.
    Exr,
    /// Portable float map, 32-bit float RGB.
    Pfm,
    /// PNG, 8-bit sRGB.
    Png,
}

impl Format {
    /// The format for a path's extension, if supported.
    pub fn from_path(path: &Path) -> Option<Format> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "exr" => Some(Format::Exr),
            "pfm" => Some(Format::Pfm),
            "png" => Some(Format::Png),
            _ => None,
        }
    }
}

/// The sRGB transfer function of a linear value clamped to [0, 1], as an 8-bit code.
pub fn srgb8(v: f32) -> u8 {
    let v = if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5).clamp(0.0, 255.0) as u8
}

/// 8-bit sRGB RGB bytes of an image.
pub fn to_srgb8(img: &RgbImage) -> Vec<u8> {
    img.data.iter().flat_map(|p| p.map(srgb8)).collect()
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes `img` to `path` in the format its extension names, atomically.
pub fn write_image(path: &Path, img: &RgbImage) -> Result<(), String> {
    let fmt = Format::from_path(path).ok_or_else(|| {
        format!(
            "{}: unknown image format (use .exr, .pfm or .png)",
            path.display()
        )
    })?;
    let tmp = temp_path(path);
    let result = write_format(&tmp, fmt, img)
        .and_then(|_| std::fs::rename(&tmp, path).map_err(|e| e.to_string()));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(|e| format!("{}: cannot write image: {e}", path.display()))
}

fn write_format(path: &Path, fmt: Format, img: &RgbImage) -> Result<(), String> {
    match fmt {
        Format::Pfm => write_pfm(path, img).map_err(|e| e.to_string()),
        Format::Exr => {
            let flat: Vec<f32> = img.data.iter().flatten().copied().collect();
            let buf = image::Rgb32FImage::from_raw(img.width, img.height, flat)
                .ok_or("image size mismatch")?;
            buf.save_with_format(path, image::ImageFormat::OpenExr)
                .map_err(|e| e.to_string())
        }
        Format::Png => {
            let buf = image::RgbImage::from_raw(img.width, img.height, to_srgb8(img))
                .ok_or("image size mismatch")?;
            buf.save_with_format(path, image::ImageFormat::Png)
                .map_err(|e| e.to_string())
        }
    }
}

fn write_pfm(path: &Path, img: &RgbImage) -> std::io::Result<()> {
    let mut w = BufWriter::new(std::fs::File::create(path)?);
    write!(w, "PF\n{} {}\n-1.0\n", img.width, img.height)?;
    // PFM stores rows bottom to top, little endian for a negative scale.
    for y in (0..img.height as usize).rev() {
        for p in &img.data[y * img.width as usize..(y + 1) * img.width as usize] {
            for c in p {
                w.write_all(&c.to_le_bytes())?;
            }
        }
    }
    w.into_inner().map_err(|e| e.into_error())?.sync_all()
}

/// Reads an EXR or PFM image as linear RGB.
pub fn read_image(path: &Path) -> Result<RgbImage, String> {
    let err = |e: String| format!("{}: cannot read image: {e}", path.display());
    match Format::from_path(path) {
        Some(Format::Pfm) => read_pfm(path).map_err(err),
        Some(Format::Exr) | Some(Format::Png) => {
            let img = image::open(path)
                .map_err(|e| err(e.to_string()))?
                .into_rgb32f();
            let (width, height) = img.dimensions();
            let data = img.pixels().map(|p| p.0).collect();
            Ok(RgbImage {
                width,
                height,
                data,
            })
        }
        None => Err(err("unknown image format".into())),
    }
}

fn read_pfm(path: &Path) -> Result<RgbImage, String> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(|e| e.to_string())?;
    let mut fields = Vec::new();
    let mut pos = 0;
    while fields.len() < 4 && pos < bytes.len() {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        fields.push(String::from_utf8_lossy(&bytes[start..pos]).into_owned());
    }
    pos += 1;
    if fields.len() < 4 || fields[0] != "PF" {
        return Err("not an RGB PFM file".into());
    }
    let width: u32 = fields[1].parse().map_err(|_| "bad width")?;
    let height: u32 = fields[2].parse().map_err(|_| "bad height")?;
    let scale: f32 = fields[3].parse().map_err(|_| "bad scale")?;
    let n = width as usize * height as usize;
    let data_bytes = bytes.get(pos..pos + n * 12).ok_or("file too short")?;
    let mut data = vec![[0.0f32; 3]; n];
    for (i, chunk) in data_bytes.chunks_exact(4).enumerate() {
        let b = [chunk[0], chunk[1], chunk[2], chunk[3]];
        let v = if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        };
        let (row, col, c) = (i / 3 / width as usize, i / 3 % width as usize, i % 3);
        data[(height as usize - 1 - row) * width as usize + col][c] = v;
    }
    Ok(RgbImage {
        width,
        height,
        data,
    })
}

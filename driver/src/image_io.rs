//! Writing images: EXR and PFM (linear float RGB), PNG (8-bit sRGB, clamped). Reading (for
//! textures, environment maps and `tessera compare`) is the scene crate's
//! [`tessera_scene::image`], re-exported here.
//!
//! Writes are atomic: the image goes to a temporary file beside the target, which is then renamed
//! over it, so a reader never sees half a file and a failed write leaves the old file intact.
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

pub use tessera_scene::image::{read_image, Format, RgbImage};

/// The sRGB transfer function of a linear value clamped to [0, 1], as an 8-bit code.
pub(crate) fn srgb8(v: f32) -> u8 {
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

pub(crate) fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes a file atomically: `write` fills a temporary file beside `path`, which is then renamed
/// over `path`; on any failure the temporary file is removed and `path` is left as it was.
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), String> {
    let tmp = temp_path(path);
    let result = write(&tmp).and_then(|_| std::fs::rename(&tmp, path).map_err(|e| e.to_string()));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Writes `img` to `path` in the format its extension names, atomically.
pub fn write_image(path: &Path, img: &RgbImage) -> Result<(), String> {
    let fmt = Format::from_path(path).ok_or_else(|| {
        format!(
            "{}: unknown image format (use .exr, .pfm or .png)",
            path.display()
        )
    })?;
    write_atomic(path, |tmp| write_format(tmp, fmt, img))
        .map_err(|e| format!("{}: cannot write image: {e}", path.display()))
}

/// Writes 8-bit sRGB pixels (`width * height * 3` bytes) to a PNG at `path`, atomically (for
/// previews drawn on after conversion, e.g. overlays).
pub fn write_png8(path: &Path, width: u32, height: u32, rgb: Vec<u8>) -> Result<(), String> {
    let buf = image::RgbImage::from_raw(width, height, rgb)
        .ok_or_else(|| format!("{}: image size mismatch", path.display()))?;
    write_atomic(path, |tmp| {
        buf.save_with_format(tmp, image::ImageFormat::Png)
            .map_err(|e| e.to_string())
    })
    .map_err(|e| format!("{}: cannot write image: {e}", path.display()))
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

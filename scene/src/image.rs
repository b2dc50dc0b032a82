//! Reading images: EXR and PFM (linear float RGB), RGBE `.hdr` (Radiance, linear) and PNG (8-bit
//! codes scaled to [0, 1]), for textures and environment maps. Writing lives in the driver.
use std::io::Read;
use std::path::Path;

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

/// Whether a path names an RGBE (Radiance `.hdr`) image, which is read but never written.
fn is_rgbe(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("hdr"))
}

/// Reads an EXR, PFM or RGBE `.hdr` image as linear RGB (a PNG is read as its 8-bit sRGB codes
/// scaled to [0, 1], not linearized).
pub fn read_image(path: &Path) -> Result<RgbImage, String> {
    let err = |e: String| format!("{}: cannot read image: {e}", path.display());
    match Format::from_path(path) {
        Some(Format::Pfm) => read_pfm(path).map_err(err),
        Some(Format::Exr | Format::Png) => read_decoded(path).map_err(err),
        None if is_rgbe(path) => read_rgbe(path).map_err(err),
        None => Err(err("unknown image format".into())),
    }
}

/// Reads a format the `image` crate decodes (EXR, PNG) as RGB f32.
fn read_decoded(path: &Path) -> Result<RgbImage, String> {
    to_rgb_image(image::open(path).map_err(|e| e.to_string())?)
}

/// Reads an RGBE (Radiance) image. Both signatures of the format are accepted: `#?RADIANCE`
/// (what the `image` crate's decoder expects) and `#?RGBE` (what Mitsuba and others write);
/// the rest of the file is the same.
fn read_rgbe(path: &Path) -> Result<RgbImage, String> {
    let mut bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    const RGBE: &[u8] = b"#?RGBE";
    if bytes.starts_with(RGBE)
        && bytes
            .get(RGBE.len())
            .is_some_and(|b| b.is_ascii_whitespace())
    {
        bytes.splice(..RGBE.len(), b"#?RADIANCE".iter().copied());
    }
    to_rgb_image(
        image::load_from_memory_with_format(&bytes, image::ImageFormat::Hdr)
            .map_err(|e| e.to_string())?,
    )
}

fn to_rgb_image(img: image::DynamicImage) -> Result<RgbImage, String> {
    let img = img.into_rgb32f();
    let (width, height) = img.dimensions();
    let data = img.pixels().map(|p| p.0).collect();
    Ok(RgbImage {
        width,
        height,
        data,
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2x3 RGBE file with signature `sig`, flat (uncompressed) scanlines, top row first;
    /// pixel (x, y) has value (x + 1) * 2^y in red, half that in green, a quarter in blue.
    fn rgbe_file(sig: &str) -> Vec<u8> {
        let mut b = format!("{sig}\nFORMAT=32-bit_rle_rgbe\n\n-Y 3 +X 2\n").into_bytes();
        for y in 0..3i32 {
            for x in 0..2u8 {
                // Mantissas 128, 64, 32 and exponent byte e mean (0.5, 0.25, 0.125) * 2^(e - 128).
                let e = (128 + 1 + y + i32::from(x)) as u8;
                b.extend_from_slice(&[128, 64, 32, e]);
            }
        }
        b
    }

    #[test]
    fn reads_rgbe_with_either_signature() {
        let dir = std::env::temp_dir().join(format!("tessera-rgbe-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for sig in ["#?RADIANCE", "#?RGBE"] {
            let path = dir.join("t.hdr");
            std::fs::write(&path, rgbe_file(sig)).unwrap();
            let img = read_image(&path).unwrap_or_else(|e| panic!("{sig}: {e}"));
            assert_eq!((img.width, img.height), (2, 3));
            for y in 0..3usize {
                for x in 0..2usize {
                    let want = (x as f32 + 1.0) * 2f32.powi(y as i32);
                    let got = img.data[y * 2 + x];
                    for (c, f) in [(0, 1.0), (1, 0.5), (2, 0.25)] {
                        let rel = (got[c] - want * f).abs() / (want * f);
                        assert!(
                            rel < 0.01,
                            "{sig} ({x}, {y}) channel {c}: {got:?} vs {want}"
                        );
                    }
                }
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

//! Reading images: EXR and PFM (linear float RGB), RGBE `.hdr` (Radiance, linear), and the 8-bit
//! formats PNG, JPEG, BMP and TGA (codes scaled to [0, 1], not decoded: see [`is_srgb_coded`]),
//! for textures and environment maps. Writing lives in the driver.
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

/// The extensions of the 8-bit formats read but never written, besides PNG.
const EIGHT_BIT_READ_ONLY: [&str; 4] = ["jpg", "jpeg", "bmp", "tga"];

/// Whether a path names an 8-bit image (PNG, JPEG, BMP, TGA): Mitsuba 3 marks every such file
/// sRGB-encoded, so a texture decodes its values to linear unless told they are raw.
pub fn is_srgb_coded(path: &Path) -> bool {
    Format::from_path(path) == Some(Format::Png) || is_eight_bit_read_only(path)
}

fn is_eight_bit_read_only(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
        EIGHT_BIT_READ_ONLY
            .iter()
            .any(|x| e.eq_ignore_ascii_case(x))
    })
}

/// Reads an EXR, PFM or RGBE `.hdr` image as linear RGB; a PNG, JPEG, BMP or TGA is read as its
/// 8-bit codes scaled to [0, 1], not linearized (greyscale is spread to RGB, alpha dropped).
pub fn read_image(path: &Path) -> Result<RgbImage, String> {
    let err = |e: String| format!("{}: cannot read image: {e}", path.display());
    match Format::from_path(path) {
        Some(Format::Pfm) => read_pfm(path).map_err(err),
        Some(Format::Exr | Format::Png) => read_decoded(path).map_err(err),
        None if is_rgbe(path) => read_rgbe(path).map_err(err),
        None if is_eight_bit_read_only(path) => read_decoded(path).map_err(err),
        None => Err(err("unknown image format".into())),
    }
}

/// Reads a format the `image` crate decodes (EXR, PNG, JPEG, BMP, TGA) as RGB f32. The format
/// is recognised by the file's first bytes where it has a signature, as Mitsuba 3 does (a JPEG
/// named `.png` still loads), and by the extension otherwise (TGA has none).
fn read_decoded(path: &Path) -> Result<RgbImage, String> {
    to_rgb_image(decode_file(path)?)
}

/// The image at `path` as the `image` crate decodes it (see [`read_decoded`]).
fn decode_file(path: &Path) -> Result<image::DynamicImage, String> {
    image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| e.to_string())?
        .decode()
        .map_err(|e| e.to_string())
}

/// An image as a texture reads it: the 8-bit codes themselves where the file holds 8 bits per
/// channel (greyscale spread to RGB, alpha dropped), else linear floats as [`read_image`] gives.
#[derive(Clone, Debug, PartialEq)]
pub enum TextureImage {
    /// 8-bit codes, row-major, top row first; code `k` is the value `k / 255` of [`read_image`].
    Codes {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
        /// Pixels.
        data: Vec<[u8; 3]>,
    },
    /// Anything else (float formats, 16-bit PNGs).
    Float(RgbImage),
}

/// Reads an image for a texture: as [`read_image`] does, but an 8-bit file keeps its codes, so
/// that the texture turns each of 256 codes into its value once instead of every channel of
/// every pixel, and no float copy of the image is made.
pub fn read_texture_image(path: &Path) -> Result<TextureImage, String> {
    if !is_srgb_coded(path) {
        return read_image(path).map(TextureImage::Float);
    }
    let err = |e: String| format!("{}: cannot read image: {e}", path.display());
    let img = decode_file(path).map_err(err)?;
    use image::DynamicImage::{ImageLuma8, ImageLumaA8, ImageRgb8, ImageRgba8};
    match img {
        ImageLuma8(_) | ImageLumaA8(_) | ImageRgb8(_) | ImageRgba8(_) => {
            let img = img.into_rgb8();
            let (width, height) = img.dimensions();
            let data = img.pixels().map(|p| p.0).collect();
            Ok(TextureImage::Codes {
                width,
                height,
                data,
            })
        }
        other => to_rgb_image(other).map(TextureImage::Float).map_err(err),
    }
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

    fn texture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../scenes/textures")
            .join(name)
    }

    #[test]
    fn eight_bit_formats_read_their_codes() {
        // tess_rgb.{bmp,tga,jpg} hold tess_rgb.png's pixels (scripts/make_8bit_textures.py):
        // the lossless ones exactly, the JPEG (quality 100) within a few codes.
        let png = read_image(&texture("tess_rgb.png")).unwrap();
        assert_eq!((png.width, png.height), (5, 4));
        // Known codes: the red channel of the top row is 17, 70, 123, 176, 229.
        let top: Vec<f32> = png.data[..5].iter().map(|p| p[0] * 255.0).collect();
        assert_eq!(top, [17.0, 70.0, 123.0, 176.0, 229.0]);
        for (name, codes) in [
            ("tess_rgb.bmp", 0.0),
            ("tess_rgb.tga", 0.0),
            ("tess_rgb.jpg", 3.0),
        ] {
            let img = read_image(&texture(name)).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!((img.width, img.height), (png.width, png.height), "{name}");
            let worst = img
                .data
                .iter()
                .zip(&png.data)
                .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() * 255.0))
                .fold(0.0f32, f32::max);
            assert!(worst <= codes + 1e-3, "{name}: off by {worst} codes");
            // Control: the image upside down is not the PNG.
            let flipped = (0..img.data.len()).any(|i| {
                let (x, y) = (i % 5, i / 5);
                let j = (3 - y) * 5 + x;
                (0..3).any(|c| (img.data[j][c] - png.data[i][c]).abs() * 255.0 > codes + 1.0)
            });
            assert!(flipped, "{name}: flipping it changes nothing");
        }
        for (name, srgb) in [
            ("a.png", true),
            ("a.JPG", true),
            ("a.jpeg", true),
            ("a.bmp", true),
            ("a.tga", true),
            ("a.exr", false),
            ("a.hdr", false),
            ("a.pfm", false),
        ] {
            assert_eq!(is_srgb_coded(Path::new(name)), srgb, "{name}");
        }
    }

    #[test]
    fn texture_codes_are_the_float_reading_times_255() {
        for name in [
            "tess_rgb.png",
            "tess_grey.png",
            "tess_rgb.jpg",
            "tess_rgb.bmp",
            "tess_rgb.tga",
            "tiles.png",
            "bumps.png",
        ] {
            let float = read_image(&texture(name)).unwrap();
            let TextureImage::Codes {
                width,
                height,
                data,
            } = read_texture_image(&texture(name)).unwrap()
            else {
                panic!("{name}: not read as 8-bit codes");
            };
            assert_eq!((width, height), (float.width, float.height), "{name}");
            // The float reading of an RGB image is `k / 255` bit for bit; of a greyscale one
            // (the image crate converts those by another route) within one unit in the last
            // place, and the texture then takes the correctly rounded `k / 255` as for RGB.
            let ulps = if name.contains("grey") || name == "bumps.png" {
                1
            } else {
                0
            };
            for (c, f) in data.iter().zip(&float.data) {
                for ch in 0..3 {
                    let want = (f32::from(c[ch]) / 255.0).to_bits();
                    assert!(
                        want.abs_diff(f[ch].to_bits()) <= ulps,
                        "{name}: {c:?} {f:?}"
                    );
                }
            }
        }
        let exr = read_texture_image(&texture("tess_linear.exr")).unwrap();
        assert!(matches!(exr, TextureImage::Float(_)));
    }

    #[test]
    fn eight_bit_formats_are_recognised_by_content() {
        // A JPEG named .png (and a PNG named .jpg) reads as the file it is.
        let dir = std::env::temp_dir().join(format!("tessera-sniff-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for (from, to) in [("tess_rgb.jpg", "jpeg.png"), ("tess_rgb.png", "png.jpg")] {
            std::fs::copy(texture(from), dir.join(to)).unwrap();
            let want = read_image(&texture(from)).unwrap();
            let got = read_image(&dir.join(to)).unwrap_or_else(|e| panic!("{to}: {e}"));
            assert_eq!(got, want, "{to}");
        }
        // Control: bytes of no format named .png are an error naming the file.
        std::fs::write(dir.join("junk.png"), b"not an image at all").unwrap();
        let e = read_image(&dir.join("junk.png")).unwrap_err();
        assert!(e.contains("junk.png") && !e.contains('\n'), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
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

//! A frame as the bytes of a file: PNG (exposure, then the sRGB curve of `tessera render`'s PNG
//! outputs) and EXR (the linear floats as they are, as `tessera render -o x.exr` writes them).
use crate::state::Frame;
use std::io::Cursor;
use tessera::image_io::{to_srgb8, RgbImage};

/// Exposures accepted, in stops.
pub const EXPOSURE_RANGE: f64 = 20.0;

/// The frame tone-mapped at `exposure` stops (the linear values times `2^exposure`).
pub fn png(frame: &Frame, exposure: f64) -> Result<Vec<u8>, String> {
    let k = exposure.exp2() as f32;
    let img = RgbImage {
        width: frame.width,
        height: frame.height,
        data: frame.rgb.iter().map(|p| p.map(|c| c * k)).collect(),
    };
    let buf = image::RgbImage::from_raw(frame.width, frame.height, to_srgb8(&img))
        .ok_or("image size mismatch")?;
    let mut out = Cursor::new(Vec::new());
    buf.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

/// The frame's linear values as an OpenEXR file.
pub fn exr(frame: &Frame) -> Result<Vec<u8>, String> {
    let flat: Vec<f32> = frame.rgb.iter().flatten().copied().collect();
    let buf = image::Rgb32FImage::from_raw(frame.width, frame.height, flat)
        .ok_or("image size mismatch")?;
    let mut out = Cursor::new(Vec::new());
    buf.write_to(&mut out, image::ImageFormat::OpenExr)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

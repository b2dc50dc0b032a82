//! Labels on PNG previews (`tessera render --overlay`): a translucent band along the bottom
//! with two lines of text (integrator, sampler / spp, time, resolution), and optionally the tile
//! grid (`--overlay-grid`) and a rectangle (`--overlay-crop x0,y0,x1,y1`).
//!
//! Only 8-bit sRGB PNG outputs get an overlay; EXR and PFM data are never touched. The text size
//! follows the image ([`text_size`]), so the label reads the same at 256x256 and at 4K; the band
//! covers rows [`label_band`]`..height`, the full width, whatever the text says.
use crate::text::{Anchor, TextPainter};
use tiny_skia::{Color, Pixmap, PremultipliedColorU8};

/// What to draw.
#[derive(Clone, Debug, Default)]
pub struct Overlay {
    /// The label's two lines (empty: no label).
    pub lines: Vec<String>,
    /// Tile edge for grid lines (`None`: no grid).
    pub grid: Option<u32>,
    /// Rectangle `[x0, y0, x1, y1)` in pixels (`None`: none).
    pub crop: Option<[u32; 4]>,
}

/// Text height in pixels for a `width x height` image: 4% of the shorter side, at least 10 px,
/// and at most width / 22 so a 40-character line fits.
pub fn text_size(width: u32, height: u32) -> f32 {
    (0.04 * width.min(height) as f32)
        .max(10.0)
        .min(width as f32 / 22.0)
}

/// First row of the label band (two lines of text with padding) of a `width x height` image.
pub fn label_band(width: u32, height: u32) -> u32 {
    let s = text_size(width, height);
    let band = (2.0 * 1.25 * s + 0.8 * s).ceil() as u32;
    height.saturating_sub(band)
}

/// Width of grid lines and of the crop rectangle's edge: 1 px up to 512 px images, then more.
pub fn line_width(width: u32, height: u32) -> u32 {
    (width.max(height) / 512).max(1)
}

/// Parses `x0,y0,x1,y1` (pixels, x0 < x1, y0 < y1).
pub fn parse_crop(s: &str) -> Result<[u32; 4], String> {
    let v: Vec<u32> = s
        .split(',')
        .map(|p| p.trim().parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("--overlay-crop expects x0,y0,x1,y1 in pixels, found \"{s}\""))?;
    match v[..] {
        [x0, y0, x1, y1] if x0 < x1 && y0 < y1 => Ok([x0, y0, x1, y1]),
        _ => Err(format!(
            "--overlay-crop expects x0,y0,x1,y1 with x0 < x1 and y0 < y1, found \"{s}\""
        )),
    }
}

/// Blends `color` (straight RGB) with opacity `a` into pixel `i` of an RGB8 buffer.
fn blend(rgb: &mut [u8], i: usize, color: [u8; 3], a: f32) {
    for k in 0..3 {
        let d = rgb[3 * i + k] as f32;
        rgb[3 * i + k] = (d + (color[k] as f32 - d) * a).round().clamp(0.0, 255.0) as u8;
    }
}

/// Draws `ov` into an 8-bit sRGB image (`rgb`: `width * height * 3` bytes, row-major).
pub fn apply(rgb: &mut [u8], width: u32, height: u32, ov: &Overlay) {
    let (w, h) = (width as usize, height as usize);
    if rgb.len() != w * h * 3 || w == 0 || h == 0 {
        return;
    }
    let lw = line_width(width, height);
    if let Some(t) = ov.grid.filter(|t| *t > 0) {
        for y in 0..height {
            for x in 0..width {
                let on = (x % t < lw && x > 0) || (y % t < lw && y > 0);
                if on {
                    blend(rgb, y as usize * w + x as usize, [255, 255, 255], 0.4);
                }
            }
        }
    }
    if let Some([x0, y0, x1, y1]) = ov.crop {
        let (x1, y1) = (x1.min(width), y1.min(height));
        for y in y0.min(height)..y1 {
            for x in x0.min(width)..x1 {
                let edge = x < x0 + lw || x + lw >= x1 || y < y0 + lw || y + lw >= y1;
                if edge {
                    blend(rgb, y as usize * w + x as usize, [255, 40, 40], 1.0);
                }
            }
        }
    }
    if ov.lines.is_empty() {
        return;
    }
    let band = label_band(width, height);
    for i in band as usize * w..w * h {
        blend(rgb, i, [0, 0, 0], 0.6);
    }
    let (Some(painter), Some(mut pm)) = (TextPainter::new(), Pixmap::new(width, height - band))
    else {
        return;
    };
    // The band as an opaque pixmap: the text is blended in, then copied back.
    for (p, src) in pm
        .pixels_mut()
        .iter_mut()
        .zip(rgb[band as usize * w * 3..].chunks(3))
    {
        if let Some(c) = PremultipliedColorU8::from_rgba(src[0], src[1], src[2], 255) {
            *p = c;
        }
    }
    let s = text_size(width, height);
    let pad = 0.4 * s;
    for (k, line) in ov.lines.iter().take(2).enumerate() {
        let baseline = pad + painter.cap_height(s) + k as f32 * 1.25 * s + 0.1 * s;
        painter.draw(
            &mut pm,
            line,
            (pad, baseline),
            s,
            Anchor::Left,
            Color::WHITE,
        );
    }
    for (dst, p) in rgb[band as usize * w * 3..].chunks_mut(3).zip(pm.pixels()) {
        let c = p.demultiply();
        dst.copy_from_slice(&[c.red(), c.green(), c.blue()]);
    }
}

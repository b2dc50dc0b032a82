//! The false-colour difference image of `tessera compare --diff`: each pixel's relative error
//! `e = mean over R, G, B of |a - b| / (|b| + 0.01)` (`b` the reference) on a logarithmic
//! viridis scale spanning four decades, with a labelled colour bar. The top of the scale is the
//! decade above the largest error (at least 1e-3); smaller errors, including zero, take the
//! darkest colour. Pixels non-finite in either image are magenta.
use std::path::Path;
use tessera::image_io::{write_png8, RgbImage};
use tessera::text::{Anchor, TextPainter};
use tiny_skia::{Color, Pixmap, PremultipliedColorU8};

/// Decades the colour scale spans.
const DECADES: i32 = 4;
/// Colour of pixels non-finite in either image.
const NONFINITE: [u8; 3] = [255, 0, 255];
/// Viridis at t = 0, 1/8, ..., 1 (linearly interpolated in between).
const VIRIDIS: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 44, 122],
    [59, 81, 139],
    [44, 113, 142],
    [33, 144, 141],
    [39, 173, 129],
    [92, 200, 99],
    [170, 220, 50],
    [253, 231, 37],
];

/// The colour of `t` in [0, 1].
fn viridis(t: f64) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (VIRIDIS.len() - 1) as f64;
    let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    [0, 1, 2].map(|c| (a[c] as f64 + (b[c] as f64 - a[c] as f64) * f).round() as u8)
}

/// Relative error of each pixel (`None` where either image is not finite).
pub(crate) fn relative_errors(a: &RgbImage, b: &RgbImage) -> Vec<Option<f64>> {
    a.data
        .iter()
        .zip(&b.data)
        .map(|(p, q)| {
            if !(p.iter().chain(q).all(|v| v.is_finite())) {
                return None;
            }
            let e: f64 = (0..3)
                .map(|c| (p[c] as f64 - q[c] as f64).abs() / ((q[c] as f64).abs() + 0.01))
                .sum();
            Some(e / 3.0)
        })
        .collect()
}

/// The decade range `[lo, hi]` (log10) of the colour scale for these errors.
pub fn scale(errors: &[Option<f64>]) -> (i32, i32) {
    let max = errors.iter().flatten().fold(0.0f64, |m, &e| m.max(e));
    let hi = if max > 0.0 {
        (max.log10().ceil() as i32).max(-3)
    } else {
        -3
    };
    (hi - DECADES, hi)
}

fn put(pm: &mut Pixmap, x: u32, y: u32, rgb: [u8; 3]) {
    let w = pm.width();
    if let Some(c) = PremultipliedColorU8::from_rgba(rgb[0], rgb[1], rgb[2], 255) {
        if let Some(p) = pm.pixels_mut().get_mut((y * w + x) as usize) {
            *p = c;
        }
    }
}

/// Draws the difference image of `a` against the reference `b` (same size).
pub(crate) fn draw_diff(a: &RgbImage, b: &RgbImage) -> Option<Pixmap> {
    let errs = relative_errors(a, b);
    let (lo, hi) = scale(&errs);
    // Small images are enlarged by whole pixels so the bar and labels fit beside them.
    let zoom = (256 / a.width.max(a.height).max(1)).clamp(1, 16);
    let (iw, ih) = (a.width * zoom, a.height * zoom);
    let (margin, top, bar_w, labels_w) = (10u32, 34u32, 18u32, 56u32);
    let bar_h = ih.max(160);
    let width = (margin + iw + 16 + bar_w + labels_w).max(430);
    let height = top + bar_h.max(ih) + 34;
    let mut pm = Pixmap::new(width, height)?;
    pm.fill(Color::WHITE);
    for (i, e) in errs.iter().enumerate() {
        let rgb = match e {
            None => NONFINITE,
            Some(e) if *e > 0.0 => viridis((e.log10() - lo as f64) / (hi - lo) as f64),
            Some(_) => viridis(0.0),
        };
        let (x, y) = (i as u32 % a.width, i as u32 / a.width);
        for dy in 0..zoom {
            for dx in 0..zoom {
                put(&mut pm, margin + x * zoom + dx, top + y * zoom + dy, rgb);
            }
        }
    }
    let bx = margin + iw + 16;
    for y in 0..bar_h {
        let t = 1.0 - y as f64 / (bar_h - 1).max(1) as f64;
        for x in 0..bar_w {
            put(&mut pm, bx + x, top + y, viridis(t));
        }
    }
    let Some(tp) = TextPainter::new() else {
        return Some(pm);
    };
    let black = Color::from_rgba8(20, 20, 20, 255);
    let title = "relative error |a-b|/(|b|+0.01), mean of R,G,B (log scale)";
    tp.draw(
        &mut pm,
        title,
        (margin as f32, 22.0),
        13.0,
        Anchor::Left,
        black,
    );
    for d in lo..=hi {
        let t = (d - lo) as f32 / (hi - lo) as f32;
        let y = top as f32 + (1.0 - t) * (bar_h - 1) as f32;
        for x in 0..4 {
            put(&mut pm, bx + bar_w + x, y.round() as u32, [20, 20, 20]);
        }
        let label = format!("1e{d}");
        let yb = y + tp.cap_height(12.0) / 2.0;
        let at = ((bx + bar_w + 7) as f32, yb.clamp(12.0, height as f32 - 2.0));
        tp.draw(&mut pm, &label, at, 12.0, Anchor::Left, black);
    }
    let note = format!(
        "below 1e{lo}: darkest; magenta: not finite; max {:.3e}",
        errs.iter().flatten().fold(0.0f64, |m, &e| m.max(e))
    );
    let at = (margin as f32, (height - 10) as f32);
    tp.draw(&mut pm, &note, at, 12.0, Anchor::Left, black);
    Some(pm)
}

/// Draws the difference image and writes it as a PNG, atomically.
pub fn write_diff(path: &Path, a: &RgbImage, b: &RgbImage) -> Result<(), String> {
    let err = |e: String| format!("{}: cannot write difference image: {e}", path.display());
    let pm = draw_diff(a, b).ok_or_else(|| err("cannot draw".into()))?;
    // Opaque, so the premultiplied bytes are the straight RGB bytes.
    let rgb: Vec<u8> = pm
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    write_png8(path, pm.width(), pm.height(), rgb)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_and_colours() {
        assert_eq!(scale(&[Some(0.0), None]), (-7, -3));
        assert_eq!(scale(&[Some(0.5), Some(0.01)]), (-4, 0));
        assert_eq!(scale(&[Some(3.0)]), (-3, 1));
        assert_eq!(viridis(0.0), VIRIDIS[0]);
        assert_eq!(viridis(1.0), VIRIDIS[8]);
        assert_eq!(viridis(f64::NAN), VIRIDIS[0]);
    }
}

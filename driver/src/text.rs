//! Text for plots: glyphs of the embedded DejaVu Sans subset (printable ASCII and a few symbols;
//! see `driver/assets/DejaVuSans-LICENSE.txt`) rasterized by ab_glyph and blended into a pixmap.
use ab_glyph::{point, Font, FontRef, PxScale, ScaleFont};
use tiny_skia::{Color, Pixmap, PremultipliedColorU8};

static FONT_DATA: &[u8] = include_bytes!("../assets/DejaVuSans-subset.ttf");

/// Draws text with an embedded font.
pub struct TextPainter {
    font: FontRef<'static>,
}

/// Where the given point is relative to the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// The point is the left end of the baseline.
    Left,
    /// The point is the middle of the baseline.
    Center,
    /// The point is the right end of the baseline.
    Right,
}

impl TextPainter {
    /// The painter, or `None` if the embedded font cannot be parsed (it always can; plots then
    /// simply have no text rather than failing).
    pub fn new() -> Option<TextPainter> {
        FontRef::try_from_slice(FONT_DATA)
            .ok()
            .map(|font| TextPainter { font })
    }

    /// Advance width of `s` at `size` pixels (with kerning).
    pub fn width(&self, s: &str, size: f32) -> f32 {
        let f = self.font.as_scaled(PxScale::from(size));
        let mut w = 0.0;
        let mut last = None;
        for c in s.chars() {
            let id = f.glyph_id(c);
            if let Some(p) = last {
                w += f.kern(p, id);
            }
            w += f.h_advance(id);
            last = Some(id);
        }
        w
    }

    /// Height of capital letters at `size` pixels (for vertical centring).
    pub fn cap_height(&self, size: f32) -> f32 {
        self.font.as_scaled(PxScale::from(size)).ascent() * 0.72
    }

    /// Draws `s` with its baseline at `at.1`, anchored at `at.0`, in `color`.
    pub fn draw(
        &self,
        pixmap: &mut Pixmap,
        s: &str,
        at: (f32, f32),
        size: f32,
        anchor: Anchor,
        color: Color,
    ) {
        let (x, y) = at;
        let scale = PxScale::from(size);
        let f = self.font.as_scaled(scale);
        let mut caret = match anchor {
            Anchor::Left => x,
            Anchor::Center => x - 0.5 * self.width(s, size),
            Anchor::Right => x - self.width(s, size),
        };
        let (w, h) = (pixmap.width() as i32, pixmap.height() as i32);
        let rgb = [color.red(), color.green(), color.blue()];
        let alpha = color.alpha();
        let mut last = None;
        for c in s.chars() {
            let id = f.glyph_id(c);
            if let Some(p) = last {
                caret += f.kern(p, id);
            }
            let glyph = id.with_scale_and_position(scale, point(caret, y));
            caret += f.h_advance(id);
            last = Some(id);
            let Some(outline) = self.font.outline_glyph(glyph) else {
                continue;
            };
            let b = outline.px_bounds();
            let pixels = pixmap.pixels_mut();
            outline.draw(|gx, gy, cov| {
                let px = b.min.x as i32 + gx as i32;
                let py = b.min.y as i32 + gy as i32;
                if px < 0 || py < 0 || px >= w || py >= h {
                    return;
                }
                let k = cov.clamp(0.0, 1.0) * alpha;
                let i = (py * w + px) as usize;
                let d = pixels[i];
                let dst = [d.red(), d.green(), d.blue(), d.alpha()];
                let mix = |dst: u8, src: f32| {
                    (dst as f32 * (1.0 - k) + src * 255.0 * k)
                        .round()
                        .clamp(0.0, 255.0) as u8
                };
                let a = mix(dst[3], 1.0);
                // Premultiplied: channels may not exceed alpha.
                let out = [
                    mix(dst[0], rgb[0]).min(a),
                    mix(dst[1], rgb[1]).min(a),
                    mix(dst[2], rgb[2]).min(a),
                ];
                if let Some(p) = PremultipliedColorU8::from_rgba(out[0], out[1], out[2], a) {
                    pixels[i] = p;
                }
            });
        }
    }
}

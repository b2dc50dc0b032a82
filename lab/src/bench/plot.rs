//! The log-log plot of relMSE against wall seconds: one line per curve of a report, decade
//! ticks with labels, labelled axes, a legend, and the target relMSE as a dashed line.
use super::{curves, Row};
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use std::path::Path;
use tessera::image_io::write_atomic;
use tessera::text::{Anchor, TextPainter};
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, StrokeDash, Transform};

const WIDTH: u32 = 800;
const HEIGHT: u32 = 560;
const LEFT: f32 = 78.0;
const RIGHT: f32 = 20.0;
const TOP: f32 = 44.0;
const BOTTOM: f32 = 58.0;

/// Line colours, one per curve in order (cycled).
const PALETTE: [(u8, u8, u8); 8] = [
    (31, 119, 180),
    (214, 39, 40),
    (44, 160, 44),
    (255, 127, 14),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (23, 190, 207),
];

/// A decade range `[lo, hi]` of log10 values covering `v` (at least one decade).
fn decades(v: impl Iterator<Item = f64>) -> (i32, i32) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in v.filter(|x| x.is_finite() && *x > 0.0) {
        lo = lo.min(x.log10());
        hi = hi.max(x.log10());
    }
    if !lo.is_finite() {
        return (0, 1);
    }
    let (lo, hi) = (lo.floor() as i32, hi.ceil() as i32);
    (lo, if hi > lo { hi } else { lo + 1 })
}

fn solid(r: u8, g: u8, b: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(r, g, b, 255);
    p.anti_alias = true;
    p
}

fn line(pixmap: &mut Pixmap, pts: &[(f32, f32)], paint: &Paint, stroke: &Stroke) {
    let mut pb = PathBuilder::new();
    for (i, &(x, y)) in pts.iter().enumerate() {
        if i == 0 {
            pb.move_to(x, y);
        } else {
            pb.line_to(x, y);
        }
    }
    if let Some(path) = pb.finish() {
        pixmap.stroke_path(&path, paint, stroke, Transform::identity(), None);
    }
}

/// Draws `10^e` with a raised exponent, anchored at its right end (y axis) or centre (x axis).
fn power_of_ten(t: &TextPainter, pm: &mut Pixmap, e: i32, x: f32, y: f32, anchor: Anchor) {
    let (big, small) = (14.0, 10.0);
    let exp = if e < 0 {
        format!("\u{2212}{}", -e)
    } else {
        e.to_string()
    };
    let w = t.width("10", big) + t.width(&exp, small);
    let x0 = match anchor {
        Anchor::Left => x,
        Anchor::Center => x - w / 2.0,
        Anchor::Right => x - w,
    };
    let black = Color::from_rgba8(20, 20, 20, 255);
    t.draw(pm, "10", (x0, y), big, Anchor::Left, black);
    let x1 = x0 + t.width("10", big);
    t.draw(pm, &exp, (x1, y - 0.45 * big), small, Anchor::Left, black);
}

/// Draws the report's curves; `target` adds a dashed horizontal line at that relMSE.
pub(crate) fn render_plot(rows: &[Row], title: &str, target: Option<f64>) -> Option<Pixmap> {
    let mut pm = Pixmap::new(WIDTH, HEIGHT)?;
    pm.fill(Color::WHITE);
    let text = TextPainter::new();
    let curves = curves(rows);
    let (x0, x1) = decades(rows.iter().map(|r| r.seconds));
    let (y0, y1) = decades(rows.iter().map(|r| r.errors.relmse).chain(target));
    let (pl, pr) = (LEFT, WIDTH as f32 - RIGHT);
    let (pt, pb) = (TOP, HEIGHT as f32 - BOTTOM);
    let sx = |s: f64| pl + ((s.log10() - x0 as f64) / (x1 - x0) as f64) as f32 * (pr - pl);
    let sy = |e: f64| pb - ((e.log10() - y0 as f64) / (y1 - y0) as f64) as f32 * (pb - pt);

    // Grid: decades solid light grey, 2..9 fainter; ticks on the frame.
    let grid_major = solid(215, 215, 215);
    let grid_minor = solid(238, 238, 238);
    let thin = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    for d in x0..=x1 {
        for m in 1..10 {
            if d == x1 && m > 1 {
                break;
            }
            let x = sx(m as f64 * 10f64.powi(d));
            let p = if m == 1 { &grid_major } else { &grid_minor };
            line(&mut pm, &[(x, pt), (x, pb)], p, &thin);
        }
    }
    for d in y0..=y1 {
        for m in 1..10 {
            if d == y1 && m > 1 {
                break;
            }
            let y = sy(m as f64 * 10f64.powi(d));
            let p = if m == 1 { &grid_major } else { &grid_minor };
            line(&mut pm, &[(pl, y), (pr, y)], p, &thin);
        }
    }
    let frame = solid(40, 40, 40);
    if let Some(r) = Rect::from_ltrb(pl, pt, pr, pb) {
        let path = PathBuilder::from_rect(r);
        pm.stroke_path(&path, &frame, &thin, Transform::identity(), None);
    }
    if let Some(t) = target.filter(|t| *t > 0.0 && t.is_finite()) {
        let dashed = Stroke {
            width: 1.5,
            dash: StrokeDash::new(vec![6.0, 4.0], 0.0),
            ..Stroke::default()
        };
        line(
            &mut pm,
            &[(pl, sy(t)), (pr, sy(t))],
            &solid(90, 90, 90),
            &dashed,
        );
        if let Some(tp) = &text {
            let label = format!("target {t}");
            let c = Color::from_rgba8(70, 70, 70, 255);
            tp.draw(
                &mut pm,
                &label,
                (pl + 6.0, sy(t) - 4.0),
                12.0,
                Anchor::Left,
                c,
            );
        }
    }

    // Curves, clipped to the plot area by construction of the axis ranges.
    let wide = Stroke {
        width: 2.0,
        ..Stroke::default()
    };
    for (i, (_, c)) in curves.iter().enumerate() {
        let (r, g, b) = PALETTE[i % PALETTE.len()];
        let paint = solid(r, g, b);
        let pts: Vec<(f32, f32)> = c
            .iter()
            .filter(|r| r.seconds > 0.0 && r.errors.relmse > 0.0)
            .map(|r| (sx(r.seconds), sy(r.errors.relmse)))
            .collect();
        line(&mut pm, &pts, &paint, &wide);
        for &(x, y) in &pts {
            if let Some(dot) = PathBuilder::from_circle(x, y, 3.0) {
                pm.fill_path(&dot, &paint, FillRule::Winding, Transform::identity(), None);
            }
        }
    }

    let Some(tp) = text else { return Some(pm) };
    let black = Color::from_rgba8(20, 20, 20, 255);
    for d in x0..=x1 {
        power_of_ten(
            &tp,
            &mut pm,
            d,
            sx(10f64.powi(d)),
            pb + 22.0,
            Anchor::Center,
        );
    }
    for d in y0..=y1 {
        let y = sy(10f64.powi(d)) + tp.cap_height(14.0) / 2.0;
        power_of_ten(&tp, &mut pm, d, pl - 8.0, y, Anchor::Right);
    }
    let mid = (pl + pr) / 2.0;
    let xlabel = "wall-clock seconds (log)";
    tp.draw(
        &mut pm,
        xlabel,
        (mid, HEIGHT as f32 - 12.0),
        15.0,
        Anchor::Center,
        black,
    );
    tp.draw(
        &mut pm,
        "relMSE (log)",
        (8.0, pt - 10.0),
        15.0,
        Anchor::Left,
        black,
    );
    tp.draw(&mut pm, title, (mid, 24.0), 17.0, Anchor::Center, black);

    // Legend in the top right corner of the plot area, on white.
    let size = 13.0;
    let lw = curves
        .iter()
        .map(|(n, _)| tp.width(n, size))
        .fold(0.0f32, f32::max)
        + 44.0;
    let lh = curves.len() as f32 * 18.0 + 8.0;
    let (lx, ly) = (pr - lw - 8.0, pt + 8.0);
    if let Some(r) = Rect::from_xywh(lx, ly, lw, lh) {
        let path = PathBuilder::from_rect(r);
        pm.fill_path(
            &path,
            &solid(255, 255, 255),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
        pm.stroke_path(
            &path,
            &solid(160, 160, 160),
            &thin,
            Transform::identity(),
            None,
        );
    }
    for (i, (name, _)) in curves.iter().enumerate() {
        let (r, g, b) = PALETTE[i % PALETTE.len()];
        let y = ly + 17.0 + i as f32 * 18.0;
        let yl = y - tp.cap_height(size) / 2.0;
        line(
            &mut pm,
            &[(lx + 8.0, yl), (lx + 32.0, yl)],
            &solid(r, g, b),
            &wide,
        );
        tp.draw(&mut pm, name, (lx + 38.0, y), size, Anchor::Left, black);
    }
    Some(pm)
}

/// Draws the plot and writes it as a PNG, atomically.
pub fn write_plot(
    path: &Path,
    rows: &[Row],
    title: &str,
    target: Option<f64>,
) -> Result<(), String> {
    let err = |e: String| format!("{}: cannot write plot: {e}", path.display());
    let pm = render_plot(rows, title, target).ok_or_else(|| err("cannot draw".into()))?;
    // The background is opaque, so premultiplied bytes are the straight RGB bytes; alpha is
    // dropped and the PNG compressed hard (the plots are committed).
    let rgb: Vec<u8> = pm
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    write_atomic(path, |tmp| {
        let f = std::fs::File::create(tmp).map_err(|e| e.to_string())?;
        let enc = PngEncoder::new_with_quality(
            std::io::BufWriter::new(f),
            CompressionType::Best,
            FilterType::Adaptive,
        );
        enc.write_image(&rgb, pm.width(), pm.height(), ExtendedColorType::Rgb8)
            .map_err(|e| e.to_string())
    })
    .map_err(err)
}

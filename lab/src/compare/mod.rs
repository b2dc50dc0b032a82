//! Comparing two images of the same size: per-channel means, RMSE, relMSE, MAE, the largest
//! absolute difference and where it is, and how many pixels are not finite. `b` is the
//! reference.
//!
//! Error measures use the definitions of `tessera bench` ([`crate::bench::errors`]), over every
//! pixel and channel where both images are finite; pixels with a non-finite channel in either
//! image are counted and left out of every measure (and of the means).
pub mod diff_image;

use crate::bench::{errors, Errors};
use tessera::image_io::RgbImage;

/// The numbers `tessera compare` reports.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// Width of both images.
    pub width: u32,
    /// Height of both images.
    pub height: u32,
    /// Mean of each channel of `a` (over the pixels finite in both).
    pub mean_a: [f64; 3],
    /// Mean of each channel of `b` (over the pixels finite in both).
    pub mean_b: [f64; 3],
    /// RMSE, relMSE (mean of (a - b)^2 / (b^2 + 0.01)) and MAE.
    pub errors: Errors,
    /// Largest |a - b| of any channel.
    pub max_abs: f64,
    /// Where it is: pixel x, pixel y, channel (0 = R, 1 = G, 2 = B).
    pub max_at: (u32, u32, usize),
    /// Pixels of `a` with a non-finite channel.
    pub nonfinite_a: usize,
    /// Pixels of `b` with a non-finite channel.
    pub nonfinite_b: usize,
}

fn finite(p: &[f32; 3]) -> bool {
    p.iter().all(|v| v.is_finite())
}

/// Compares `a` with the reference `b`; an error (one line) if their sizes differ.
pub fn compare(a: &RgbImage, b: &RgbImage) -> Result<Comparison, String> {
    if (a.width, a.height) != (b.width, b.height) || a.data.len() != b.data.len() {
        return Err(format!(
            "the images differ in size: {}x{} and {}x{}",
            a.width, a.height, b.width, b.height
        ));
    }
    let nonfinite_a = a.data.iter().filter(|p| !finite(p)).count();
    let nonfinite_b = b.data.iter().filter(|p| !finite(p)).count();
    let (mut fa, mut fb) = (Vec::with_capacity(a.data.len()), Vec::new());
    let (mut sa, mut sb) = ([0.0f64; 3], [0.0f64; 3]);
    let (mut max_abs, mut max_at) = (0.0f64, (0, 0, 0));
    for (i, (p, q)) in a.data.iter().zip(&b.data).enumerate() {
        if !finite(p) || !finite(q) {
            continue;
        }
        for c in 0..3 {
            sa[c] += p[c] as f64;
            sb[c] += q[c] as f64;
            let d = (p[c] as f64 - q[c] as f64).abs();
            if d > max_abs {
                max_abs = d;
                max_at = (i as u32 % a.width, i as u32 / a.width, c);
            }
        }
        fa.push(*p);
        fb.push(*q);
    }
    let n = fa.len().max(1) as f64;
    Ok(Comparison {
        width: a.width,
        height: a.height,
        mean_a: sa.map(|s| s / n),
        mean_b: sb.map(|s| s / n),
        errors: errors(&fa, &fb),
        max_abs,
        max_at,
        nonfinite_a,
        nonfinite_b,
    })
}

const CHANNELS: [&str; 3] = ["R", "G", "B"];

impl Comparison {
    /// The report as text lines; `names` are the two files.
    pub fn to_text(&self, names: (&str, &str)) -> String {
        let m = |v: [f64; 3]| format!("{:.6} {:.6} {:.6}", v[0], v[1], v[2]);
        let (x, y, c) = self.max_at;
        format!(
            "size            {}x{}\n\
             mean A (R G B)  {}  {}\n\
             mean B (R G B)  {}  {} (reference)\n\
             RMSE            {:.6e}\n\
             relMSE          {:.6e}\n\
             MAE             {:.6e}\n\
             max abs error   {:.6e} at ({x}, {y}) channel {}\n\
             non-finite      A {} pixels, B {} pixels (left out of every measure)\n",
            self.width,
            self.height,
            m(self.mean_a),
            names.0,
            m(self.mean_b),
            names.1,
            self.errors.rmse,
            self.errors.relmse,
            self.errors.mae,
            self.max_abs,
            CHANNELS[c],
            self.nonfinite_a,
            self.nonfinite_b
        )
    }

    /// The report as one flat JSON object; `names` are the two files.
    pub fn to_json(&self, names: (&str, &str)) -> String {
        let arr = |v: [f64; 3]| format!("[{}, {}, {}]", num(v[0]), num(v[1]), num(v[2]));
        let (x, y, c) = self.max_at;
        format!(
            "{{\"a\": {}, \"b\": {}, \"width\": {}, \"height\": {}, \"mean_a\": {}, \
             \"mean_b\": {}, \"rmse\": {}, \"relmse\": {}, \"mae\": {}, \"max_abs_error\": {}, \
             \"max_abs_error_at\": [{x}, {y}], \"max_abs_error_channel\": \"{}\", \
             \"nonfinite_a\": {}, \"nonfinite_b\": {}}}\n",
            json_string(names.0),
            json_string(names.1),
            self.width,
            self.height,
            arr(self.mean_a),
            arr(self.mean_b),
            num(self.errors.rmse),
            num(self.errors.relmse),
            num(self.errors.mae),
            num(self.max_abs),
            CHANNELS[c],
            self.nonfinite_a,
            self.nonfinite_b
        )
    }
}

/// A JSON number (shortest text that reads back to the same f64), `null` if not finite.
fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else {
        "null".into()
    }
}

/// A JSON string literal.
fn json_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_is_escaped() {
        assert_eq!(json_string("a\"b\\c\n"), "\"a\\\"b\\\\c\\u000a\"");
        assert_eq!(num(f64::NAN), "null");
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(1e-12), "1e-12");
    }
}

//! `<spectrum>` values to RGB, as Mitsuba 3's RGB variants convert them.
//!
//! A wavelength:value list (`value="400:0.1, 500:0.2"`, or a file of "wavelength value"
//! lines) is interpolated linearly, integrated against the CIE 1931 colour matching functions
//! (1000 evenly spaced wavelengths over 360..830 nm, none outside the list's range), and the
//! XYZ result turned into linear sRGB. Mitsuba weighs the integral by the D65 illuminant for
//! everything but emitted light (so a flat reflectance of 0.5 becomes grey 0.5), and clamps
//! the colour to [0, 1], except for emitted light and the parameters it reads unbounded
//! (conductor indices, roughness), which are only kept non-negative. A single value is grey,
//! except for emitted light, where Mitsuba's RGB variants turn a flat spectrum into the sRGB
//! of XYZ (v, v, v), slightly purple, to match its spectral variants.

use super::cie::{CIE_MAX, CIE_MIN, CIE_SAMPLES, CIE_X, CIE_Y, CIE_Z, D65};
use super::object::Kind;

/// How a spectrum is used, which decides its conversion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SpectrumUse {
    /// Emitted light (a parameter of an `<emitter>`): no D65 weight, unbounded.
    Emitted,
    /// A parameter Mitsuba reads unbounded (an index of refraction, a roughness).
    Unbounded,
    /// Everything else (reflectances): D65 weight, clamped to [0, 1].
    Bounded,
}

/// Parameters Mitsuba 3 reads as unbounded textures: (plugin, parameter).
const UNBOUNDED: &[(&str, &str)] = &[
    ("conductor", "eta"),
    ("conductor", "k"),
    ("roughconductor", "eta"),
    ("roughconductor", "k"),
    ("roughconductor", "alpha"),
    ("roughconductor", "alpha_u"),
    ("roughconductor", "alpha_v"),
    ("roughdielectric", "alpha"),
    ("roughdielectric", "alpha_u"),
    ("roughdielectric", "alpha_v"),
    ("pplastic", "eta"),
    ("pplastic", "alpha"),
    ("pplastic", "alpha_u"),
    ("pplastic", "alpha_v"),
    ("principledthin", "eta"),
    ("hair", "sigma_a"),
    ("polarizer", "theta"),
    ("retarder", "theta"),
    ("retarder", "delta"),
];

impl SpectrumUse {
    /// The use of parameter `name` of an object of `kind` with plugin `plugin`.
    pub fn of(kind: Kind, plugin: &str, name: &str) -> Self {
        if kind == Kind::Emitter {
            SpectrumUse::Emitted
        } else if UNBOUNDED.contains(&(plugin, name)) {
            SpectrumUse::Unbounded
        } else {
            SpectrumUse::Bounded
        }
    }
}

/// The XYZ to linear sRGB matrix (rows) Mitsuba uses.
const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.240479, -1.537150, -0.498535],
    [-0.969256, 1.875991, 0.041556],
    [0.055648, -0.204043, 1.057311],
];

/// Scales the CIE curves so that a unit spectrum has luminance 1.
const CIE_Y_NORMALIZATION: f64 = 1.0 / 106.750_259_399_414_06;

/// Scales the D65 table so that it has luminance 1.
const D65_NORMALIZATION: f64 = 1.0 / 98.99741751876255;

/// Linear interpolation in one of the 5 nm tables.
fn table_at(table: &[f32; CIE_SAMPLES], w: f64) -> f64 {
    if !(CIE_MIN..=CIE_MAX).contains(&w) {
        return 0.0;
    }
    let t = (w - CIE_MIN) * ((CIE_SAMPLES - 1) as f64 / (CIE_MAX - CIE_MIN));
    let i0 = (t as usize).min(CIE_SAMPLES - 2);
    let f = t - i0 as f64;
    (1.0 - f) * f64::from(table[i0]) + f * f64::from(table[i0 + 1])
}

fn xyz_to_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_SRGB.map(|r| r[0] * xyz[0] + r[1] * xyz[1] + r[2] * xyz[2])
}

/// The RGB of a flat spectrum of value `v` used as `how`.
pub(crate) fn uniform_to_rgb(v: f64, how: SpectrumUse) -> [f64; 3] {
    match how {
        SpectrumUse::Emitted => xyz_to_srgb([v; 3]),
        _ => [v; 3],
    }
}

/// The RGB of a spectrum given as increasing `wavelengths` (nm) and `values`, used as `how`,
/// and, when that colour had to be clamped (out of gamut), the colour before clamping.
/// Needs at least two entries (checked by [`check_list`]).
pub(crate) fn list_to_rgb(
    wavelengths: &[f64],
    values: &[f64],
    how: SpectrumUse,
) -> ([f64; 3], Option<[f64; 3]>) {
    const STEPS: usize = 1000;
    let (first, last) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
    let mut xyz = [0.0; 3];
    for i in 0..STEPS {
        let w = CIE_MIN + (i as f64 / (STEPS - 1) as f64) * (CIE_MAX - CIE_MIN);
        if w < first || w > last {
            continue;
        }
        // The last entry whose wavelength is <= w, at most the second to last.
        let k = (wavelengths.partition_point(|&x| x <= w).max(1) - 1).min(wavelengths.len() - 2);
        let (w0, w1, v0, v1) = (wavelengths[k], wavelengths[k + 1], values[k], values[k + 1]);
        let mut v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
        if how != SpectrumUse::Emitted {
            v *= table_at(&D65, w) * D65_NORMALIZATION;
        }
        xyz[0] += table_at(&CIE_X, w) * v;
        xyz[1] += table_at(&CIE_Y, w) * v;
        xyz[2] += table_at(&CIE_Z, w) * v;
    }
    let scale = (CIE_MAX - CIE_MIN) * CIE_Y_NORMALIZATION / STEPS as f64;
    let rgb = xyz_to_srgb(xyz.map(|c| c * scale));
    let clamped = match how {
        SpectrumUse::Bounded => rgb.map(|c| c.clamp(0.0, 1.0)),
        _ => rgb.map(|c| c.max(0.0)),
    };
    (clamped, (clamped != rgb).then_some(rgb))
}

/// Checks a wavelength list as Mitsuba does: at least two entries, increasing wavelengths.
pub fn check_list(wavelengths: &[f64]) -> Result<(), String> {
    if wavelengths.len() < 2 {
        return Err("a spectrum needs at least two wavelength:value pairs".into());
    }
    match wavelengths.windows(2).find(|p| p[1] <= p[0]) {
        Some(p) => Err(format!(
            "wavelengths must increase ({} nm follows {} nm)",
            p[1], p[0]
        )),
        None => Ok(()),
    }
}

/// Parses `"400:0.1, 500:0.2"` (pairs separated by commas or whitespace).
pub(crate) fn parse_pairs(s: &str) -> Result<(Vec<f64>, Vec<f64>), String> {
    let mut w = Vec::new();
    let mut v = Vec::new();
    for item in super::values::split_list(s) {
        let Some((a, b)) = item.split_once(':') else {
            return Err(format!(
                "\"{item}\" is not a wavelength:value pair (a spectrum is one value, or pairs \
                 like \"400:0.1, 500:0.2\")"
            ));
        };
        w.push(super::values::parse_float(a).map_err(|m| format!("in \"{item}\": {m}"))?);
        v.push(super::values::parse_float(b).map_err(|m| format!("in \"{item}\": {m}"))?);
    }
    check_list(&w)?;
    Ok((w, v))
}

/// Parses a spectrum file: lines "wavelength value" (anything after the two numbers is
/// ignored); lines starting with `#`, and empty lines, are skipped.
pub(crate) fn parse_file(text: &str) -> Result<(Vec<f64>, Vec<f64>), String> {
    let mut w = Vec::new();
    let mut v = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let mut items = line.split_whitespace();
        let mut number = |what: &str| {
            items
                .next()
                .ok_or_else(|| format!("line {}: no {what}", n + 1))
                .and_then(|s| {
                    super::values::parse_float(s).map_err(|m| format!("line {}: {m}", n + 1))
                })
        };
        w.push(number("wavelength")?);
        v.push(number("value")?);
    }
    check_list(&w)?;
    Ok((w, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_reflectance_is_grey_and_flat_light_is_not() {
        // D65-weighted integration of a flat spectrum gives D65's own colour: white.
        let w = [360.0, 830.0];
        let (rgb, clamped) = list_to_rgb(&w, &[0.5, 0.5], SpectrumUse::Bounded);
        assert_eq!(clamped, None);
        for c in rgb {
            assert!((c - 0.5).abs() < 2e-3, "{rgb:?}");
        }
        // Emitted light is not weighted: XYZ (v, v, v) in sRGB, as a single value is.
        let (e, _) = list_to_rgb(&w, &[2.0, 2.0], SpectrumUse::Emitted);
        let u = uniform_to_rgb(2.0, SpectrumUse::Emitted);
        for i in 0..3 {
            assert!((e[i] - u[i]).abs() < 2e-2 * u[i], "{e:?} vs {u:?}");
        }
        assert!(u[0] > 2.2 && u[2] < 1.9, "{u:?}");
        assert_eq!(uniform_to_rgb(0.3, SpectrumUse::Bounded), [0.3; 3]);
    }

    #[test]
    fn bad_lists() {
        assert!(parse_pairs("400:0.1").unwrap_err().contains("at least two"));
        assert!(parse_pairs("500:0.1, 400:0.2")
            .unwrap_err()
            .contains("increase"));
        assert!(parse_pairs("400:0.1, 500").unwrap_err().contains("pair"));
        assert!(parse_pairs("400:x, 500:1").unwrap_err().contains("\"x\""));
        assert_eq!(
            parse_pairs("400:1 500:2").unwrap(),
            (vec![400.0, 500.0], vec![1.0, 2.0])
        );
        let (w, v) = parse_file("# comment\n400 0.5 extra\n\n500\t0.25\n").unwrap();
        assert_eq!((w, v), (vec![400.0, 500.0], vec![0.5, 0.25]));
        assert!(parse_file("400 0.5\n500\n").unwrap_err().contains("line 2"));
    }
}

//! The reconstruction filters with negative lobes written out in f64 from their published
//! formulas, independently of the core: the references the filter sampling and weighting tests
//! build their step tables from.

/// The Mitchell-Netravali cubic with parameters `b`, `c` (radius 2); `b = c = 1/3` is Mitchell's
/// recommendation, `b = 0, c = 1/2` Catmull-Rom.
pub fn mitchell(b: f64, c: f64, x: f64) -> f64 {
    let x = x.abs();
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x.powi(3) + (-18.0 + 12.0 * b + 6.0 * c) * x * x + 6.0
            - 2.0 * b
    } else if x < 2.0 {
        (-b - 6.0 * c) * x.powi(3)
            + (6.0 * b + 30.0 * c) * x * x
            + (-12.0 * b - 48.0 * c) * x
            + 8.0 * b
            + 24.0 * c
    } else {
        0.0
    };
    v / 6.0
}

/// The Lanczos (windowed sinc) filter with `lobes` lobes (radius `lobes`).
pub fn lanczos(lobes: f64, x: f64) -> f64 {
    let x = x.abs();
    if x < 1e-7 {
        return 1.0;
    }
    if x > lobes {
        return 0.0;
    }
    let (a, b) = (std::f64::consts::PI * x, std::f64::consts::PI * x / lobes);
    a.sin() * b.sin() / (a * b)
}

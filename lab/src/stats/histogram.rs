//! The chi-square test of a sampler on a rectangular grid of cells, shared by
//! `SphereChi2` and `PlaneChi2`: count the sampler's
//! outputs per cell, integrate the pdf over each cell, compare ([`grid_chi2`]). Each test
//! supplies only its domain: how a sample maps to a cell, and how a grid coordinate maps to
//! the point its pdf takes.

use std::fmt::Display;

use glam::Vec2;

use super::chi2::{chi2_test, Chi2Result, DEFAULT_MIN_EXPECTED};
use super::quadrature::grid_probabilities;
use super::rng::Pcg32;

/// Index of the cell containing `t ∈ [0, 1]` among `n` equal cells (clamped at the ends).
pub(crate) fn cell_index(t: f64, n: usize) -> usize {
    ((t * n as f64).floor().max(0.0) as usize).min(n - 1)
}

/// Runs a chi-square test of a sampler on the `x × y` grid (each `(start, end, cells)`, x
/// major; cell `ix * y.2 + iy`). `samples` points `u` uniform in `[0,1)^2` are drawn from a
/// [`Pcg32`] seeded with `seed`; `cell(k, u)` gives the cell of sample `k`, `Ok(None)` for a
/// failed sample (it lands nowhere), or `Err(message)` to fail the test at once. The expected
/// counts integrate `pdf(x, y)`, which returns the point it evaluated (for messages) and the
/// density there w.r.t. `dx dy`: a negative or non-finite density fails at once. Then
/// [`chi2_test`] compares the counts, and the pdf's integral is checked against the failures.
///
/// # Panics
/// If a grid dimension or `samples` is zero (`name` says which test).
pub(crate) fn grid_chi2<P: Display>(
    name: &str,
    samples: usize,
    seed: u64,
    x: (f64, f64, usize),
    y: (f64, f64, usize),
    mut cell: impl FnMut(usize, Vec2) -> Result<Option<usize>, String>,
    mut pdf: impl FnMut(f64, f64) -> (P, f64),
) -> Chi2Result {
    assert!(
        x.2 > 0 && y.2 > 0 && samples > 0,
        "{name}: bins and samples must be > 0"
    );
    let mut rng = Pcg32::new(seed);
    let mut observed = vec![0.0f64; x.2 * y.2];
    let mut failures = 0usize;
    for k in 0..samples {
        match cell(k, rng.next_vec2()) {
            Ok(Some(i)) => observed[i] += 1.0,
            Ok(None) => failures += 1,
            Err(message) => return Chi2Result::failure(message),
        }
    }

    let mut bad_pdf: Option<(P, f64)> = None;
    let mut density = |a: f64, b: f64| {
        let (p, v) = pdf(a, b);
        if !(v.is_finite() && v >= 0.0) && bad_pdf.is_none() {
            bad_pdf = Some((p, v));
        }
        v
    };
    let probs = grid_probabilities(&mut density, x, y, samples);
    if let Some((p, v)) = bad_pdf {
        return Chi2Result::failure(format!("pdf({p}) = {v} is negative or not finite"));
    }

    let n = samples as f64;
    let expected: Vec<f64> = probs.iter().map(|p| p * n).collect();
    let mut result = chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED);
    result.check_pdf_integral(probs.iter().sum(), failures);
    result
}

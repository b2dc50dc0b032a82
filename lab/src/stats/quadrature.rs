//! Adaptive Gauss–Legendre cubature of a pdf over the cells of a rectangular grid.
//!
//! The chi-square tests need the probability of every histogram cell, i.e. the integral of the
//! claimed pdf over the cell. Each cell is integrated with the tensor-product 8×8-point
//! Gauss–Legendre rule (exact for polynomials of degree 15 in each variable; for pdfs that are
//! smooth inside the cell the relative error is at the level of f64 round-off). To cope with
//! kinks and discontinuities *inside* a cell (a cone's edge, a triangle's diagonal, a lobe
//! narrower than a cell) the rule is applied adaptively: a rectangle's estimate is compared with
//! the sum over its four quadrants, and quadrants are split recursively until the estimates of
//! two consecutive levels agree within the tolerance (halved at each level), or down to 1/1024
//! of the cell's width. Requiring two agreeing levels guards against the accidental agreement
//! that one comparison is prone to when a jump sits between the nodes; for smooth pdfs it
//! costs 21 applications of the rule (1344 pdf evaluations) per cell.
//!
//! The tolerance is expressed in samples: the error of a cell's expected count `E` is targeted
//! at `0.01 * sqrt(max(E, 1))`, 1% of its Poisson standard deviation, which shifts the
//! expectation of the chi-square statistic by less than 1e-4 per cell.
//!
//! Accuracy in practice: for pdfs smooth inside the cells (including jumps that lie on cell
//! boundaries, like a hemisphere's edge) the cell probabilities are exact to ~1e-12 relative.
//! A jump along a curve through a cell drives the refinement to the depth limit (1/1024 of the
//! cell's width), leaving an error of about 1e-4 of that cell's probability (measured: 1.4e-4
//! for a triangle's diagonal through 10 × 10 cells, 5e-5 for a cone's edge through a row of
//! cells), at a cost of ~1e6 pdf evaluations per such cell. That is negligible against the
//! Poisson noise of the counts below ~1e8 expected samples per cell. Features that fall
//! entirely between the 64 nodes of a cell can be missed, so cells should not be much larger
//! than the pdf's smallest feature.

/// Positive Gauss–Legendre nodes on `[-1, 1]` (8-point rule; the others are their negatives).
const GL_NODES: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_2,
];
/// Weights of [`GL_NODES`] (the same for the negated nodes; they sum to 1 per half).
const GL_WEIGHTS: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_26,
];

/// Deepest subdivision level (cells split into quadrants at most this many times).
const MAX_DEPTH: u32 = 10;

/// Most subdivisions spent on one grid cell: a safety valve against pdfs that never look
/// smooth (noise), about 4 million pdf evaluations. A jump along a curve needs ~3 000.
const MAX_REFINEMENTS_PER_CELL: u32 = 1 << 14;

/// Node and weight `i` (0..8) of the 8-point rule on `[-1, 1]`, in increasing order.
fn gl_point(i: usize) -> (f64, f64) {
    if i < 4 {
        (-GL_NODES[3 - i], GL_WEIGHTS[3 - i])
    } else {
        (GL_NODES[i - 4], GL_WEIGHTS[i - 4])
    }
}

/// The 8×8-point tensor Gauss–Legendre rule for `∫∫ f` over `[x0, x1] × [y0, y1]`.
fn gauss_legendre_8x8(
    f: &mut dyn FnMut(f64, f64) -> f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
) -> f64 {
    let (cx, hx) = (0.5 * (x0 + x1), 0.5 * (x1 - x0));
    let (cy, hy) = (0.5 * (y0 + y1), 0.5 * (y1 - y0));
    let mut sum = 0.0;
    for i in 0..8 {
        let (xi, wi) = gl_point(i);
        let x = cx + hx * xi;
        let mut row = 0.0;
        for j in 0..8 {
            let (yj, wj) = gl_point(j);
            row += wj * f(x, cy + hy * yj);
        }
        sum += wi * row;
    }
    sum * hx * hy
}

/// Refines `whole` (the 8×8 estimate over the rectangle) by comparing it with its quadrants.
#[allow(clippy::too_many_arguments)]
fn refine(
    f: &mut dyn FnMut(f64, f64) -> f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    whole: f64,
    tol: f64,
    depth: u32,
    parent_agreed: bool,
    budget: &mut u32,
) -> f64 {
    *budget = budget.saturating_sub(1);
    let (xm, ym) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let quads = [
        (x0, xm, y0, ym),
        (xm, x1, y0, ym),
        (x0, xm, ym, y1),
        (xm, x1, ym, y1),
    ];
    let parts = quads.map(|(a, b, c, d)| gauss_legendre_8x8(f, a, b, c, d));
    let sum: f64 = parts.iter().sum();
    let agreed = (sum - whole).abs() <= tol;
    if depth + 1 >= MAX_DEPTH || *budget == 0 || !sum.is_finite() || (agreed && parent_agreed) {
        return sum;
    }
    quads
        .iter()
        .zip(parts)
        .map(|(&(a, b, c, d), part)| {
            refine(f, a, b, c, d, part, 0.5 * tol, depth + 1, agreed, budget)
        })
        .sum()
}

/// `∫∫ f` over `[x0, x1] × [y0, y1]`, adaptive to absolute tolerance `tol` (see module docs).
#[cfg(test)]
fn integrate_rect(
    f: &mut dyn FnMut(f64, f64) -> f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    tol: f64,
) -> f64 {
    let whole = gauss_legendre_8x8(f, x0, x1, y0, y1);
    refine(
        f,
        x0,
        x1,
        y0,
        y1,
        whole,
        tol,
        0,
        false,
        &mut MAX_REFINEMENTS_PER_CELL.clone(),
    )
}

/// Probability of each cell of the `nx × ny` grid over `[x0, x1] × [y0, y1]` under the density
/// `f` (w.r.t. `dx dy`), index `ix * ny + iy`, with the per-cell tolerance derived from
/// `samples` as in the module docs.
pub(crate) fn grid_probabilities(
    f: &mut dyn FnMut(f64, f64) -> f64,
    (x0, x1, nx): (f64, f64, usize),
    (y0, y1, ny): (f64, f64, usize),
    samples: usize,
) -> Vec<f64> {
    let n = samples.max(1) as f64;
    let dx = (x1 - x0) / nx as f64;
    let dy = (y1 - y0) / ny as f64;
    let mut probs = Vec::with_capacity(nx * ny);
    for ix in 0..nx {
        let (a, b) = (
            x0 + dx * ix as f64,
            if ix + 1 == nx {
                x1
            } else {
                x0 + dx * (ix + 1) as f64
            },
        );
        for iy in 0..ny {
            let (c, d) = (
                y0 + dy * iy as f64,
                if iy + 1 == ny {
                    y1
                } else {
                    y0 + dy * (iy + 1) as f64
                },
            );
            let whole = gauss_legendre_8x8(f, a, b, c, d);
            let tol = 0.01 * (n * whole.abs()).max(1.0).sqrt() / n;
            let mut budget = MAX_REFINEMENTS_PER_CELL;
            probs.push(refine(f, a, b, c, d, whole, tol, 0, false, &mut budget));
        }
    }
    probs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rule_is_exact_for_degree_15() {
        let w: f64 = (0..8).map(|i| gl_point(i).1).sum();
        assert!((w - 2.0).abs() < 1e-15);
        // ∫∫ x^14 y^15 over [0,1]^2 = 1/(15 * 16).
        let v = gauss_legendre_8x8(&mut |x, y| x.powi(14) * y.powi(15), 0.0, 1.0, 0.0, 1.0);
        assert!((v - 1.0 / 240.0).abs() < 1e-15, "{v}");
        // Smooth, non-polynomial: ∫∫ exp(x + y) over [0,1]^2 = (e - 1)^2.
        let want = (std::f64::consts::E - 1.0).powi(2);
        let v = gauss_legendre_8x8(&mut |x, y| (x + y).exp(), 0.0, 1.0, 0.0, 1.0);
        assert!((v - want).abs() < 1e-13 * want, "{v}");
    }

    #[test]
    fn adaptive_handles_discontinuities() {
        // Indicator of the triangle x + y < 0.7 (diagonal cuts the square): area 0.245.
        let mut evals = 0usize;
        let mut f = |x: f64, y: f64| {
            evals += 1;
            if x + y < 0.7 {
                1.0
            } else {
                0.0
            }
        };
        let v = integrate_rect(&mut f, 0.0, 1.0, 0.0, 1.0, 1e-7);
        assert!((v - 0.245).abs() < 1e-4, "{v}");
        assert!(evals < 2_000_000, "{evals}");
        // Disc of radius 0.3 (curved edge): pi * 0.09.
        let mut g = |x: f64, y: f64| {
            if (x - 0.5).powi(2) + (y - 0.5).powi(2) < 0.09 {
                1.0
            } else {
                0.0
            }
        };
        let v = integrate_rect(&mut g, 0.0, 1.0, 0.0, 1.0, 1e-7);
        let want = std::f64::consts::PI * 0.09;
        assert!((v - want).abs() < 1e-4 * want, "{v} vs {want}");
    }

    #[test]
    fn grid_cells_sum_to_the_integral() {
        let mut f = |x: f64, y: f64| 2.0 * x * (1.0 + 0.0 * y);
        let p = grid_probabilities(&mut f, (0.0, 1.0, 4), (0.0, 1.0, 3), 1000);
        assert_eq!(p.len(), 12);
        // Column ix holds ((ix+1)^2 - ix^2)/16 spread over 3 rows.
        for ix in 0..4 {
            for iy in 0..3 {
                let want = ((ix + 1) * (ix + 1) - ix * ix) as f64 / 16.0 / 3.0;
                assert!((p[ix * 3 + iy] - want).abs() < 1e-14);
            }
        }
    }
}

//! Chi-square test of a sampler of the unit square against its area pdf.
//!
//! # Method
//!
//! The same test as `SphereChi2`, on the domain `[0,1]^2` instead of the
//! sphere: for position samplers whose output can be mapped to the square (triangle
//! barycentrics, a parametrized surface's `(u, v)`, a 2-D warp).
//!
//! 1. `samples` points `u` uniform in `[0,1)^2` are drawn from a [`Pcg32`](super::rng::Pcg32) seeded with `seed`
//!    and passed to the sampler; the returned points are counted in `bins_x × bins_y` equal
//!    cells. A failed sample (`None`) lands nowhere; the pdf must then integrate to the
//!    probability of success.
//! 2. The expected count of a cell is `samples · ∫_cell pdf(p) dp`, computed with adaptive
//!    8×8-point Gauss–Legendre cubature (essentially exact for pdfs smooth inside cells; about
//!    1e-4 of a cell's probability at worst for a jump inside a cell, such as a triangle's
//!    diagonal; see `quadrature.rs`).
//! 3. [`chi2_test`](super::chi2::chi2_test) compares observed and expected counts with pooling of sparse cells.
//! 4. The pdf's integral over the square is reported as `pdf_integral` and must be 1 (within
//!    [`PDF_INTEGRAL_TOLERANCE`](super::chi2::PDF_INTEGRAL_TOLERANCE)) if the sampler never failed,
//!    at most 1 otherwise.
//!
//! Immediate failures (p = 0, with a message): a point outside `[0,1]^2` (beyond 1e-6) or not
//! finite, a sample in a cell where the pdf integrates to 0, and a negative or non-finite pdf
//! value.

use glam::Vec2;

use super::chi2::Chi2Result;
use super::histogram::{cell_index, grid_chi2};

/// How far outside `[0,1]^2` a sampled point may be (f32 round-off) before the test fails.
const DOMAIN_TOLERANCE: f64 = 1e-6;

/// Chi-square test configuration for samplers of points in `[0,1]^2`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlaneChi2 {
    /// Number of cells along x.
    pub bins_x: usize,
    /// Number of cells along y.
    pub bins_y: usize,
    /// Number of sampler invocations.
    pub samples: usize,
}

impl Default for PlaneChi2 {
    /// 10 × 10 cells with 1e6 samples.
    fn default() -> Self {
        PlaneChi2 {
            bins_x: 10,
            bins_y: 10,
            samples: 1_000_000,
        }
    }
}

impl PlaneChi2 {
    /// Runs the test: `sample` maps a uniform point of `[0,1)^2` to a point of `[0,1]^2` (or
    /// `None` if sampling failed), `pdf` is the claimed density w.r.t. area on the square.
    /// Deterministic for a given `seed`. The test fails when `p_value < alpha`.
    ///
    /// # Panics
    /// If any of the bin counts or `samples` is zero.
    pub fn run(
        &self,
        mut sample: impl FnMut(Vec2) -> Option<Vec2>,
        pdf: impl Fn(Vec2) -> f64,
        seed: u64,
    ) -> Chi2Result {
        let (nx, ny) = (self.bins_x, self.bins_y);
        let inside = |t: f64| (-DOMAIN_TOLERANCE..=1.0 + DOMAIN_TOLERANCE).contains(&t);
        let cell = |k: usize, u: Vec2| {
            let Some(p) = sample(u) else {
                return Ok(None);
            };
            let (x, y) = (f64::from(p.x), f64::from(p.y));
            if !(inside(x) && inside(y)) {
                return Err(format!(
                    "sample {k} (u = {u}): the sampler returned {p}, outside [0,1]^2"
                ));
            }
            Ok(Some(cell_index(x, nx) * ny + cell_index(y, ny)))
        };
        grid_chi2(
            "PlaneChi2",
            self.samples,
            seed,
            (0.0, 1.0, nx),
            (0.0, 1.0, ny),
            cell,
            |x, y| {
                let p = Vec2::new(x as f32, y as f32);
                (p, pdf(p))
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x with density 2x (inverse cdf sqrt), y uniform.
    fn linear_x(u: Vec2) -> Option<Vec2> {
        Some(Vec2::new(u.x.sqrt(), u.y))
    }

    fn linear_pdf(p: Vec2) -> f64 {
        2.0 * f64::from(p.x)
    }

    #[test]
    fn uniform_passes() {
        let r = PlaneChi2::default().run(Some, |_| 1.0, 11);
        assert!(r.passes(0.01), "{r}");
        assert_eq!(r.dof, 99);
        assert!((r.pdf_integral.unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn linear_density_passes_and_uniform_pdf_is_rejected() {
        let test = PlaneChi2::default();
        let r = test.run(linear_x, linear_pdf, 12);
        assert!(r.passes(0.01), "{r}");
        let r = test.run(linear_x, |_| 1.0, 12);
        assert!(r.p_value < 1e-6, "{r}");
        assert!(r.message.is_none(), "{r}");
    }

    #[test]
    fn two_percent_wrong_pdf_is_rejected() {
        // Normalized, at most 2% off (in y): only the statistic can see it.
        let wrong = |p: Vec2| linear_pdf(p) * (1.0 + 0.04 * (f64::from(p.y) - 0.5));
        let r = PlaneChi2::default().run(linear_x, wrong, 13);
        assert!((r.pdf_integral.unwrap() - 1.0).abs() < 1e-6, "{r}");
        assert!(r.message.is_none(), "{r}");
        assert!(r.p_value < 1e-3, "{r}");
    }

    #[test]
    fn triangle_with_diagonal_inside_cells() {
        // Uniform on the triangle x + y <= 1 (barycentrics by folding): density 2 there. The
        // diagonal runs through the cells, so this exercises the adaptive cubature and the
        // pooling of the thin cells along it.
        let fold = |u: Vec2| {
            Some(if u.x + u.y > 1.0 {
                Vec2::new(1.0 - u.x, 1.0 - u.y)
            } else {
                u
            })
        };
        let pdf = |p: Vec2| if p.x + p.y <= 1.0 { 2.0 } else { 0.0 };
        let test = PlaneChi2 {
            bins_x: 10,
            bins_y: 10,
            samples: 200_000,
        };
        let r = test.run(fold, pdf, 15);
        assert!(r.passes(0.01), "{r}");
        assert!((r.pdf_integral.unwrap() - 1.0).abs() < 1e-4, "{r}");

        // Forgetting to fold puts samples where the pdf is 0.
        let r = test.run(Some, pdf, 14);
        assert_eq!(r.p_value, 0.0);
        assert!(r.message.is_some(), "{r}");
    }

    #[test]
    fn failures_and_bad_points() {
        let test = PlaneChi2 {
            bins_x: 8,
            bins_y: 8,
            samples: 100_000,
        };
        // Rejection sampling of the disc of radius 1/2 (probability of success pi/4).
        let disc = |u: Vec2| ((u - Vec2::splat(0.5)).length_squared() <= 0.25).then_some(u);
        let disc_pdf = |p: Vec2| {
            if (p - Vec2::splat(0.5)).length_squared() <= 0.25 {
                1.0
            } else {
                0.0
            }
        };
        let r = test.run(disc, disc_pdf, 15);
        assert!(r.passes(0.01), "{r}");
        assert!(
            (r.pdf_integral.unwrap() - std::f64::consts::FRAC_PI_4).abs() < 1e-4,
            "{r}"
        );
        // Normalizing the pdf as if the sampler never failed is detected.
        let r = test.run(disc, |p| disc_pdf(p) / std::f64::consts::FRAC_PI_4, 15);
        assert!(r.p_value < 1e-6, "{r}");

        let r = test.run(|u| Some(u * 1.5), |_| 1.0, 15);
        assert_eq!(r.p_value, 0.0);
        assert!(r.message.as_deref().unwrap().contains("outside"), "{r}");
    }
}

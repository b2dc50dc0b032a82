//! Chi-square test of a direction sampler against its solid-angle pdf on the unit sphere.
//!
//! # Method (Nori's `warptest` / Mitsuba 3's `ChiSquareTest`)
//!
//! The sphere is cut into `theta_bins × phi_bins` cells that are uniform in `cos θ ∈ [-1, 1]`
//! (θ measured from +z) and in `φ ∈ [0, 2π)` (from +x towards +y). Since the solid angle is
//! `dω = d(cos θ) dφ`, every cell has the same solid angle, `4π / (theta_bins · phi_bins)`.
//!
//! 1. `samples` points `u` uniform in `[0,1)^2` are drawn from a [`Pcg32`](super::rng::Pcg32) seeded with
//!    `rng_seed`, passed to the sampler and the returned directions are counted per cell.
//!    A sampler may fail (`None`): such a sample lands nowhere, so the observed counts sum to
//!    fewer than `samples`, and the pdf must integrate to the probability of success.
//! 2. The expected count of a cell is `samples · ∫_cell pdf(ω) dω`, integrated in
//!    `(cos θ, φ)` with adaptive 8×8-point Gauss–Legendre cubature: exact to ~1e-12 for pdfs
//!    smooth inside the cells (jumps on cell boundaries, like a hemisphere's edge, are fine),
//!    and to about 1e-4 of the cell's probability for a jump through a cell (a cone's edge);
//!    see `quadrature.rs`.
//! 3. [`chi2_test`](super::chi2::chi2_test) compares the two with pooling of sparse cells.
//! 4. The integral of the pdf over the sphere is reported as `pdf_integral`. If the sampler
//!    never failed it must be 1 within
//!    [`PDF_INTEGRAL_TOLERANCE`](super::chi2::PDF_INTEGRAL_TOLERANCE); if it did fail, it must not
//!    exceed 1. Otherwise the test fails with a message.
//!
//! Immediate failures (p = 0, with a message): a sample in a cell where the pdf integrates to
//! 0, a returned vector that is not unit length (within 1e-3) or not finite, and a pdf value
//! that is negative or not finite.
//!
//! Choose the resolution so that the cells resolve the pdf's features, and enough samples for
//! most cells to expect well over 5 samples; Nori uses 10 × 20 cells, and 1e6 samples detect
//! pdf errors of about 2%.

use std::f64::consts::TAU;

use glam::{Vec2, Vec3};

use super::chi2::Chi2Result;
use super::histogram::{cell_index, grid_chi2};

/// Largest accepted `| |ω| - 1 |` for a sampled direction.
const UNIT_LENGTH_TOLERANCE: f64 = 1e-3;

/// Chi-square test configuration for samplers of directions on the unit sphere.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SphereChi2 {
    /// Number of cells in `cos θ ∈ [-1, 1]` (equal solid angle).
    pub theta_bins: usize,
    /// Number of cells in `φ ∈ [0, 2π)`.
    pub phi_bins: usize,
    /// Number of sampler invocations.
    pub samples: usize,
}

impl Default for SphereChi2 {
    /// Nori's resolution (10 × 20 cells) with 1e6 samples.
    fn default() -> Self {
        SphereChi2 {
            theta_bins: 10,
            phi_bins: 20,
            samples: 1_000_000,
        }
    }
}

impl SphereChi2 {
    /// Runs the test: `sample` maps a uniform point of `[0,1)^2` to a unit direction (or `None`
    /// if sampling failed), `pdf` is the claimed density of the directions w.r.t. solid angle.
    /// Deterministic for a given `rng_seed`. The test fails when `p_value < alpha`.
    ///
    /// # Panics
    /// If any of the bin counts or `samples` is zero.
    pub fn run(
        &self,
        mut sample: impl FnMut(Vec2) -> Option<Vec3>,
        pdf: impl Fn(Vec3) -> f64,
        rng_seed: u64,
    ) -> Chi2Result {
        let (nt, np) = (self.theta_bins, self.phi_bins);
        let cell = |k: usize, u: Vec2| {
            let Some(w) = sample(u) else {
                return Ok(None);
            };
            let (x, y, z) = (f64::from(w.x), f64::from(w.y), f64::from(w.z));
            let len = (x * x + y * y + z * z).sqrt();
            if len.is_nan() || (len - 1.0).abs() > UNIT_LENGTH_TOLERANCE {
                return Err(format!(
                    "sample {k} (u = {u}): the sampler returned {w}, which is not a unit vector"
                ));
            }
            let mut phi = y.atan2(x);
            if phi < 0.0 {
                phi += TAU;
            }
            let it = cell_index(0.5 * (z + 1.0), nt);
            let ip = cell_index(phi / TAU, np);
            Ok(Some(it * np + ip))
        };
        grid_chi2(
            "SphereChi2",
            self.samples,
            rng_seed,
            (-1.0, 1.0, nt),
            (0.0, TAU, np),
            cell,
            |z, phi| {
                let s = (1.0 - z * z).max(0.0).sqrt();
                let w = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
                (w, pdf(w))
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::{FRAC_1_PI, PI, TAU as TAU32};

    const INV_4PI: f64 = 1.0 / (4.0 * std::f64::consts::PI);
    const INV_2PI: f64 = 1.0 / TAU;

    fn uniform_sphere(u: Vec2) -> Vec3 {
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = TAU32 * u.y;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    fn cosine_hemisphere(u: Vec2) -> Vec3 {
        let r = u.x.sqrt();
        let phi = TAU32 * u.y;
        Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt())
    }

    fn cosine_pdf(w: Vec3) -> f64 {
        if w.z > 0.0 {
            f64::from(w.z * FRAC_1_PI)
        } else {
            0.0
        }
    }

    fn uniform_hemisphere_pdf(w: Vec3) -> f64 {
        if w.z > 0.0 {
            INV_2PI
        } else {
            0.0
        }
    }

    #[test]
    fn uniform_sphere_passes() {
        let r = SphereChi2::default().run(|u| Some(uniform_sphere(u)), |_| INV_4PI, 1);
        assert!(r.passes(0.01), "{r}");
        assert_eq!(r.dof, 199);
        assert!((r.pdf_integral.unwrap() - 1.0).abs() < 1e-12, "{r}");
    }

    #[test]
    fn cosine_hemisphere_passes_and_uniform_pdf_is_rejected() {
        let test = SphereChi2::default();
        let r = test.run(|u| Some(cosine_hemisphere(u)), cosine_pdf, 2);
        assert!(r.passes(0.01), "{r}");
        assert!((r.pdf_integral.unwrap() - 1.0).abs() < 1e-6, "{r}");
        // The lower hemisphere's 100 cells have expectation 0 and are left out.
        assert_eq!(r.dof, 99);

        let r = test.run(|u| Some(cosine_hemisphere(u)), uniform_hemisphere_pdf, 2);
        assert!(r.p_value < 1e-6, "{r}");
        assert!(r.message.is_none(), "rejected by the statistic itself: {r}");
    }

    #[test]
    fn sparse_cells_near_the_horizon_are_pooled() {
        // Each of the 20 cells with cos θ in [0, 0.2] has probability (0.2² / 2) / π · (2π / 20)
        // = 0.002 under the cosine pdf: with 2000 samples it expects 4 < 5, so the 20 are pooled
        // into one cell (expecting 80). The next row expects 12 per cell.
        let test = SphereChi2 {
            theta_bins: 10,
            phi_bins: 20,
            samples: 2000,
        };
        let r = test.run(|u| Some(cosine_hemisphere(u)), cosine_pdf, 7);
        assert_eq!(r.pooled_cells, 20, "{r}");
        assert_eq!(r.dof, 80, "80 unpooled cells + 1 pooled cell - 1");
        assert!(r.passes(0.01), "{r}");
    }

    #[test]
    fn two_percent_wrong_pdf_is_rejected() {
        // Still normalized, but up to 2% off: only the chi-square statistic can see it.
        let wrong = |w: Vec3| INV_4PI * (1.0 + 0.02 * f64::from(w.z));
        let r = SphereChi2::default().run(|u| Some(uniform_sphere(u)), wrong, 3);
        assert!((r.pdf_integral.unwrap() - 1.0).abs() < 1e-12, "{r}");
        assert!(r.message.is_none(), "{r}");
        assert!(r.p_value < 1e-3, "{r}");

        // 2% too large everywhere: the integral check catches it, and so would the statistic.
        let r = SphereChi2::default().run(|u| Some(uniform_sphere(u)), |_| 1.02 * INV_4PI, 3);
        assert_eq!(r.p_value, 0.0);
        assert!(
            r.message.as_deref().unwrap().contains("integrates to 1.02"),
            "{r}"
        );
        let p = statistic_p_value(r.statistic, r.dof);
        assert!(p < 1e-6, "{r}");
    }

    /// The p-value of a statistic alone (bypassing the integral check).
    fn statistic_p_value(x: f64, dof: usize) -> f64 {
        use statrs::distribution::{ChiSquared, ContinuousCDF};
        ChiSquared::new(dof as f64).unwrap().sf(x)
    }

    #[test]
    fn cone_with_edge_inside_cells() {
        // Uniform cone around +z with cos θmax = 0.83: the edge cuts through a row of cells, so
        // the expected counts need the adaptive cubature.
        let cos_max = 0.83f32;
        let sample = |u: Vec2| {
            let z = 1.0 - u.x * (1.0 - cos_max);
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = TAU32 * u.y;
            Some(Vec3::new(r * phi.cos(), r * phi.sin(), z))
        };
        let pdf = |w: Vec3| {
            if w.z >= cos_max {
                1.0 / (2.0 * PI as f64 * (1.0 - f64::from(cos_max)))
            } else {
                0.0
            }
        };
        let test = SphereChi2 {
            theta_bins: 20,
            phi_bins: 20,
            samples: 200_000,
        };
        let r = test.run(sample, pdf, 4);
        assert!(r.passes(0.01), "{r}");
        assert!((r.pdf_integral.unwrap() - 1.0).abs() < 1e-4, "{r}");
    }

    #[test]
    fn failing_sampler() {
        // A sampler that gives up a quarter of the time (u.x < 0.25).
        let sample =
            |u: Vec2| (u.x >= 0.25).then(|| uniform_sphere(Vec2::new((u.x - 0.25) / 0.75, u.y)));
        let test = SphereChi2 {
            theta_bins: 10,
            phi_bins: 20,
            samples: 200_000,
        };
        let r = test.run(sample, |_| 0.75 * INV_4PI, 5);
        assert!(r.passes(0.01), "{r}");
        assert!((r.pdf_integral.unwrap() - 0.75).abs() < 1e-12);
        // Ignoring the failures in the pdf is detected.
        let r = test.run(sample, |_| INV_4PI, 5);
        assert!(r.p_value < 1e-6, "{r}");
    }

    #[test]
    fn impossible_samples_and_bad_vectors_fail_immediately() {
        let test = SphereChi2 {
            theta_bins: 10,
            phi_bins: 20,
            samples: 10_000,
        };
        let r = test.run(|u| Some(uniform_sphere(u)), uniform_hemisphere_pdf, 6);
        assert_eq!(r.p_value, 0.0);
        assert!(
            r.message.as_deref().unwrap().contains("expected count 0"),
            "{r}"
        );

        let r = test.run(|u| Some(1.01 * uniform_sphere(u)), |_| INV_4PI, 6);
        assert_eq!(r.p_value, 0.0);
        assert!(
            r.message.as_deref().unwrap().contains("not a unit vector"),
            "{r}"
        );

        let r = test.run(
            |u| Some(uniform_sphere(u)),
            |w| if w.z > 0.9 { -1.0 } else { INV_4PI },
            6,
        );
        assert_eq!(r.p_value, 0.0);
        assert!(r.message.as_deref().unwrap().contains("negative"), "{r}");
    }

    #[test]
    fn p_values_are_calibrated() {
        // Under the null hypothesis p is uniform on [0, 1]: a harness that always answers p ~ 1
        // (or p ~ 0) is broken. 40 independent runs of a correct sampler.
        let test = SphereChi2 {
            theta_bins: 5,
            phi_bins: 10,
            samples: 20_000,
        };
        let ps: Vec<f64> = (0..40)
            .map(|seed| {
                test.run(|u| Some(uniform_sphere(u)), |_| INV_4PI, 100 + seed)
                    .p_value
            })
            .collect();
        let mean = ps.iter().sum::<f64>() / ps.len() as f64;
        let below = ps.iter().filter(|&&p| p < 0.25).count();
        // Mean of 40 U(0,1) has sd 0.046; the count below 0.25 is Binomial(40, 0.25): mean 10, sd 2.7.
        assert!((0.35..0.65).contains(&mean), "{ps:?}");
        assert!((2..=20).contains(&below), "{ps:?}");
    }
}

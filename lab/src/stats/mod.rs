//! Statistical test harness for Tessera's correctness tests.
//!
//! Monte Carlo code cannot be checked against exact outputs: a sampler, a BSDF or a rendered
//! image is correct when its *distribution* (or its *expected value*) is right. This module
//! turns such claims into hypothesis tests, in the style of Nori's and Mitsuba 3's `chi2` and
//! Student t-tests:
//!
//! - [`chi2`]: Pearson chi-square goodness of fit of binned counts against expected counts,
//!   with Nori-style pooling of cells whose expectation is too small, and the Šidák correction
//!   for running many tests at one overall significance level.
//! - [`sphere_chi2`]: chi-square test of a direction sampler against its claimed solid-angle
//!   pdf, on equal-area cells of the unit sphere.
//! - [`bsdf_chi2`]: the same for a BSDF's `sample` against its `pdf`, delta components by
//!   their discrete probabilities, with per-sample `eval`/`pdf` consistency checks.
//! - [`albedo_ttest`]: Student t-test of a BSDF's mean sampled weight (its directional albedo)
//!   against a reference, as Nori's BSDF `ttest` does.
//! - [`plane_chi2`]: the same for a sampler of the unit square `[0,1]^2` against its area pdf.
//! - [`ttest`]: Student's one-sample t-test of a mean against a reference value (from samples
//!   or from accumulated sums), and Welch's two-sample t-test.
//! - [`rng`]: the small deterministic PCG32 generator that drives the samplers under test.
//!
//! Every test reports a p-value: the probability, if the code is correct, of a result at least
//! as extreme as the one observed. A test *fails* when `p_value < alpha` (use [`sidak_alpha`] to
//! split an overall `alpha` between several tests). The module's own unit tests show both
//! sides: correct samplers and means pass, and wrong pdfs (by as little as 2%) and biased means
//! are rejected.

pub mod albedo_ttest;
pub mod bsdf_chi2;
pub mod chi2;
mod histogram;
pub mod plane_chi2;
mod quadrature;
pub mod rng;
pub mod sphere_chi2;
pub mod ttest;

pub use albedo_ttest::{albedo_t_test, luminance, AlbedoReference, AlbedoTTest};
pub use bsdf_chi2::{sampled_albedo, BsdfChi2};
pub use chi2::{chi2_test, sidak_alpha, Chi2Result, DEFAULT_MIN_EXPECTED, PDF_INTEGRAL_TOLERANCE};
pub use plane_chi2::PlaneChi2;
pub use rng::Pcg32;
pub use sphere_chi2::SphereChi2;
pub use ttest::{t_test_from_sums, t_test_mean, t_test_mean_f32, welch_test, Moments, TTest};

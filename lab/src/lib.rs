//! Tessera's lab: the tools that check and measure the renderer rather than render. The
//! chi-square and t-test harnesses ([`stats`]), Nori-style test files ([`testfile`]), error
//! against time ([`bench`](mod@bench)), image comparison ([`compare`]) and one pixel's path in detail
//! ([`debug_pixel`]). The `tessera` command's `test`, `bench` and `compare` run on it.
//!
//! # Example
//!
//! ```
//! use tessera_lab::stats::{chi2_test, t_test_from_sums, DEFAULT_MIN_EXPECTED};
//! // Counts of 6000 die rolls against a fair die's expectation.
//! let observed = [1010.0, 980.0, 1003.0, 1022.0, 991.0, 994.0];
//! assert!(chi2_test(&observed, &[1000.0; 6], DEFAULT_MIN_EXPECTED).p_value > 0.01);
//! // A loaded die is told apart.
//! let loaded = [1300.0, 940.0, 940.0, 940.0, 940.0, 940.0];
//! assert!(chi2_test(&loaded, &[1000.0; 6], DEFAULT_MIN_EXPECTED).p_value < 1e-6);
//! // Student's t-test of a mean from the sums a renderer keeps per pixel: 0, 1, 2, 3.
//! let t = t_test_from_sums(4.0, 6.0, 14.0, 1.5);
//! assert!(t.passes(0.01));
//! ```
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]
pub mod bench;
pub mod compare;
pub mod debug_pixel;
pub mod stats;
pub mod testfile;

//! Tessera's lab: the tools that check and measure the renderer rather than render. The
//! chi-square and t-test harnesses ([`stats`]), Nori-style test files ([`testfile`]), error
//! against time ([`bench`](mod@bench)), image comparison ([`compare`]) and one pixel's path in detail
//! ([`debug_pixel`]). The `tessera` command's `test`, `bench` and `compare` run on it.
// `!(x > 0.0)` rejects NaN along with the values it names (as in the core).
#![allow(clippy::neg_cmp_op_on_partial_ord)]
pub mod bench;
pub mod compare;
pub mod debug_pixel;
pub mod stats;
pub mod testfile;

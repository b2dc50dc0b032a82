//! The command line's end-to-end tests, in one test binary (one link of the workspace instead of
//! one per file). Each file beside this one is a module named after it (`cargo test --release -p
//! tessera-cli --test cli adaptive::` runs one file's tests); the suite's
//! `every_file_is_a_module` (tests/tests/main.rs) fails when a file here is missing from the
//! list below. `support/` and `scenes/` are shared
//! helpers.

mod adaptive;
mod adaptive_reuse;
mod aov;
mod api;
mod bench;
mod bench_fresh;
mod cli_errors;
mod compare;
mod determinism;
mod fuzz_regressions;
mod info;
mod limits;
mod overlay;
mod probe;
mod progressive;
mod reuse;
mod sampler_cli;
mod scenes;
mod split_merge;
mod support;
mod target_error;
mod view_cli;

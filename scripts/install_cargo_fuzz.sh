#!/bin/sh
# Installs cargo-fuzz (the `cargo fuzz` subcommand) at a pinned version, for the fuzz targets in
# fuzz/. Running them needs a nightly toolchain: `cargo +nightly fuzz run <target>`.
set -eu
cargo install cargo-fuzz --locked --version 0.13.2

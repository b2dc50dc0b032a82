//! Fuzz target: PLY bytes (ASCII or binary) -> `load_ply`: a validated mesh or a one-line
//! `InputError`, never a panic or an allocation sized by a count in the header. The input is
//! written to a scratch file (the loader reads files).
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    let path = common::put("input.ply", data);
    match tessera_scene::mesh::load_ply(&path) {
        Ok(m) => m.validate(&path).expect("a loaded mesh validates"),
        Err(e) => assert!(!e.to_string().contains('\n'), "multi-line error: {e}"),
    }
});

//! Fuzz target: OBJ bytes -> `load_obj` and `load_obj_with_materials` (the two paths a scene
//! uses). Each must give a validated mesh or a one-line `InputError`, never a panic. The input
//! is written to a scratch file (the loaders read files; `mtllib m.mtl` finds a real library).
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    let path = common::put("input.obj", data);
    for r in [
        tessera_scene::mesh::load_obj(&path).map(|m| vec![m]),
        tessera_scene::mesh::load_obj_with_materials(&path).map(|p| {
            p.plain
                .into_iter()
                .chain(p.by_material.into_iter().map(|x| x.1))
                .collect()
        }),
    ] {
        match r {
            Ok(meshes) => {
                for m in meshes {
                    m.validate(&path).expect("a loaded mesh validates");
                }
            }
            Err(e) => assert!(!e.to_string().contains('\n'), "multi-line error: {e}"),
        }
    }
});

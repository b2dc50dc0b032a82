//! Every integration test of the workspace's crates working together, in one test binary:
//! one binary links the workspace once instead of once per file, which halves the suite's build.
//! Each file beside this one is a module named after it (`cargo test --release -p tessera-tests
//! --test suite bvh8::` runs one file's tests); `every_file_is_a_module` fails when a
//! file here or in cli/tests is missing from its list.

mod analytic;
mod aov_agreement;
mod bsdf_chalmers;
mod bsdf_conductor;
mod bsdf_dielectric;
mod bsdf_inputs;
mod bsdf_maps;
mod bsdf_mitsuba_eval;
mod bsdf_plastic;
mod bsdf_polarized;
mod bsdf_principled;
mod bsdf_principled_thin;
mod bsdf_testfiles;
mod bsdf_wakame;
mod bumpmap_agreement;
mod bvh;
mod bvh8;
mod bvh8_mixed;
mod camera_batch;
mod cameras;
mod cbox_agreement;
mod course_integrators;
mod curves_analytic;
mod curves_mitsuba;
mod cylinder_chi2;
mod dialect_wakame;
mod dialects;
mod docs;
mod emitters_analytic;
mod emitters_chi2;
mod env_compensation;
mod envmap_agreement;
mod escapes;
mod film_crop;
mod filter_agreement;
mod filter_weights;
mod hetero_agreement;
mod hetero_analytic;
mod hetero_chi2;
mod hetero_volumes;
mod instances;
mod layering;
mod light_select;
mod materials_agreement;
mod media_agreement;
mod media_analytic;
mod media_inputs;
mod medium_chi2;
mod mesh_attributes;
mod mtl;
mod phase_chi2;
mod phase_mitsuba_eval;
mod projector_agreement;
mod projector_analytic;
mod real_agreement;
mod real_scenes;
mod reuse_agreement;
mod sampler_zsobol;
mod sampler_zsobol_layout;
mod sampler_zsobol_render;
mod sampling_chi2;
mod scene_casts;
mod serialized;
mod skip;
mod sphere_uv;
mod splat_agreement;
mod stress_geometry;
mod stress_materials;
mod stress_proptest;
mod stress_scale;
mod testfiles;
mod textured_light_agreement;
mod textures;
mod tri4;
mod view_api;
mod volpathmis_agreement;
mod volpathmis_analytic;

/// Cargo builds only the modules listed in `main.rs` (`autotests = false`), here and in the
/// command line's `cli/tests/`, so a test file left out of a list would never run: fail instead.
#[test]
fn every_file_is_a_module() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for here in [root.join("tests"), root.join("../cli/tests")] {
        let main = here.join("main.rs");
        let listed = std::fs::read_to_string(&main).unwrap();
        for entry in std::fs::read_dir(&here).unwrap() {
            let path = entry.unwrap().path();
            let (Some(stem), Some("rs")) = (
                path.file_stem().and_then(|s| s.to_str()),
                path.extension().and_then(|e| e.to_str()),
            ) else {
                continue;
            };
            if stem != "main" {
                assert!(
                    listed.contains(&format!("\nmod {stem};\n")),
                    "{} is not a module of {}: add `mod {stem};`",
                    path.display(),
                    main.display()
                );
            }
        }
    }
}

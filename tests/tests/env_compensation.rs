//! MIS compensation of environment maps: the scene loader makes the maps sample by compensated
//! tables exactly where every integrator the scene renders with weighs each emitter sample by
//! MIS, and a render job refuses a compensated scene with any other integrator. (That the
//! compensated tables sample their own density is `emitters_chi2.rs`; that renders with them
//! agree with Mitsuba 3 and with the emitter-only strategy, which keeps the plain tables, is
//! `envmap_agreement.rs`.)
use tessera_core::light::LightBound;
use tessera_core::render::RenderJob;
use tessera_tests::{load_file, load_file_edited};

#[test]
fn the_loader_compensates_only_for_integrators_that_weigh_by_mis() {
    let mut l = load_file("envmap.xml", &[("res", "32")]);
    assert!(l.scene.environment_compensated(), "the file's path tracer");
    for (name, on) in [
        ("path_ems", false),
        ("path_mats", false),
        ("path_half", false),
        ("direct_ems", false),
        ("direct_mats", false),
        ("ao", false),
        ("direct", true),
        ("direct_mis", true),
        ("volpath", true),
        ("path", true),
        ("path+reuse", true),
    ] {
        l.set_integrator(Some(name), None)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(l.scene.environment_compensated(), on, "{name}");
        assert_eq!(
            l.integrator.weighs_light_samples_by_mis(&l.scene),
            on,
            "{name}"
        );
    }
    // Control: a scene without an environment map has nothing to compensate.
    let cbox = load_file("cbox.xml", &[("res", "32")]);
    assert!(cbox.integrator.weighs_light_samples_by_mis(&cbox.scene));
    assert!(!cbox.scene.environment_compensated());
}

#[test]
#[should_panic(expected = "MIS-compensated")]
fn a_render_job_refuses_compensated_tables_with_an_emitter_only_integrator() {
    let l = load_file("envmap.xml", &[("res", "32")]);
    let mut ems = load_file("envmap.xml", &[("res", "32")]);
    ems.set_integrator(Some("path_ems"), None)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(l.scene.environment_compensated());
    let _ = RenderJob::new(&l.scene, &ems.integrator, 1);
}

#[test]
fn a_render_job_takes_compensated_tables_with_integrators_that_sample_no_light() {
    let l = load_file("envmap.xml", &[("res", "32")]);
    assert!(l.scene.environment_compensated());
    for name in ["ao", "normals"] {
        let mut other = load_file("envmap.xml", &[("res", "32")]);
        other
            .set_integrator(Some(name), None)
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(!other.integrator.weighs_light_samples_by_mis(&other.scene));
        assert!(
            other.integrator.may_use_compensated_environment(&l.scene),
            "{name}"
        );
        let _ = RenderJob::new(&l.scene, &other.integrator, 1);
    }
}

#[test]
fn a_render_job_takes_plain_tables_with_any_integrator() {
    let mut l = load_file("envmap.xml", &[("res", "32")]);
    let mut ems = load_file("envmap.xml", &[("res", "32")]);
    ems.set_integrator(Some("path_ems"), None)
        .unwrap_or_else(|e| panic!("{e}"));
    l.scene.set_environment_compensation(false);
    assert!(!l.scene.environment_compensated());
    let _ = RenderJob::new(&l.scene, &ems.integrator, 1);
}

#[test]
fn a_file_can_keep_the_plain_tables() {
    let edit = |t: &str| {
        t.replace(
            r#"<emitter type="envmap">"#,
            r#"<emitter type="envmap"><boolean name="mis_compensation" value="false"/>"#,
        )
    };
    let mut l = load_file_edited("envmap.xml", edit, &[("res", "32")]);
    assert!(l.integrator.weighs_light_samples_by_mis(&l.scene));
    assert!(!l.scene.environment_compensated());
    l.set_integrator(Some("volpath"), None)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!l.scene.environment_compensated());
    // Control: said true (Tessera's default), the tables are compensated.
    let edit = |t: &str| {
        t.replace(
            r#"<emitter type="envmap">"#,
            r#"<emitter type="envmap"><boolean name="mis_compensation" value="true"/>"#,
        )
    };
    let l = load_file_edited("envmap.xml", edit, &[("res", "32")]);
    assert!(l.scene.environment_compensated());
}

/// The environment's weight in light selection (material scene: a soft sky and an area light).
fn environment_weight(l: &tessera_scene::LoadedScene) -> f32 {
    let bounds = l.scene.lights().bounds();
    assert_eq!(bounds.len(), 2, "the material scene's sky and area light");
    bounds
        .iter()
        .find_map(|b| match b {
            LightBound::Environment { lum } => Some(*lum),
            _ => None,
        })
        .expect("an environment bound")
}

/// Light selection weighs a map by the light its tables sample: with compensated tables only
/// what lies above the mean (BSDF sampling finds the rest), so a soft sky beside an area light
/// takes fewer light samples; with the plain tables again, all of its light.
#[test]
fn light_selection_weighs_a_map_by_what_its_tables_sample() {
    let mut l = load_file("materials.xml", &[("res", "32")]);
    assert!(l.scene.environment_compensated());
    let compensated = environment_weight(&l);
    l.set_integrator(Some("path_ems"), None)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!l.scene.environment_compensated());
    let plain = environment_weight(&l);
    eprintln!("environment weight: compensated {compensated}, plain {plain}");
    assert!(
        compensated > 0.0 && compensated < 0.5 * plain,
        "compensated {compensated}, plain {plain}"
    );
    l.set_integrator(Some("path"), None)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(environment_weight(&l), compensated);
}

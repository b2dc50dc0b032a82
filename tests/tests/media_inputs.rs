//! Scene files with media: what loads, what is refused, and how. Every refusal is one located
//! line (`file:line:column: ...`) naming what is wrong; a parameter accepted without effect is
//! one located warning; the media and their interfaces land where the file puts them.
use tessera_core::integrator::Integrator;
use tessera_core::medium::{Medium, PhaseFunction};
use tessera_scene::load_scene_str;
use tessera_tests::scenes_dir;

fn load(body: &str, integrator: &str) -> Result<tessera_scene::LoadedScene, String> {
    let xml = format!(
        r#"<scene version="3.0.0">
  {integrator}
  <sensor type="perspective">
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  </sensor>
  {body}
</scene>"#
    );
    load_scene_str(&xml, &scenes_dir().join("media-inputs.xml"), &[]).map_err(|e| e.to_string())
}

const VOLPATH: &str = r#"<integrator type="volpath"/>"#;

fn refused(body: &str, integrator: &str, needle: &str, line: u32) {
    let e = load(body, integrator).expect_err("the scene must be refused");
    println!("{e}");
    assert!(e.contains(needle), "{e}");
    assert!(
        e.contains(&format!("media-inputs.xml:{line}:")),
        "not located at line {line}: {e}"
    );
    assert_eq!(e.lines().count(), 1, "{e}");
}

const SPHERE_WITH_MEDIUM: &str = r#"<shape type="sphere"><bsdf type="null"/>
    <medium type="homogeneous" name="interior"><float name="sigma_t" value="2"/></medium>
  </shape>"#;

#[test]
fn media_load_into_the_scene() {
    let body = r#"<medium type="homogeneous" id="fog"><rgb name="sigma_t" value="0.1, 0.2, 0.3"/>
    <float name="scale" value="2"/><phase type="hg"><float name="g" value="-0.4"/></phase></medium>
  <shape type="sphere"><bsdf type="null"/><ref name="interior" id="fog"/>
    <medium type="homogeneous" name="exterior"><boolean name="sample_emitters" value="false"/></medium>
  </shape>
  <shape type="sphere"><ref name="exterior" id="fog"/></shape>"#;
    let l = load(body, VOLPATH).expect("loads");
    let m = &l.scene.media;
    assert_eq!(m.media.len(), 2, "a referenced medium is built once");
    let Medium::Homogeneous(fog) = &m.media[0] else {
        panic!("not homogeneous")
    };
    assert!(
        (fog.sigma_t - tessera_core::Color::new(0.2, 0.4, 0.6))
            .abs()
            .max_element()
            < 1e-6
    );
    assert_eq!(
        fog.albedo.eval(glam::Vec3::ZERO),
        tessera_core::Color::splat(0.75),
        "Mitsuba's default albedo"
    );
    assert_eq!(
        fog.phase,
        PhaseFunction::Hg(tessera_core::medium::HenyeyGreenstein { g: -0.4 })
    );
    assert!(fog.sample_emitters);
    let Medium::Homogeneous(other) = &m.media[1] else {
        panic!("not homogeneous")
    };
    assert_eq!(
        other.sigma_t,
        tessera_core::Color::ONE,
        "Mitsuba's default sigma_t"
    );
    assert_eq!(other.phase, PhaseFunction::default());
    assert!(!other.sample_emitters);
    assert_eq!(m.interface(0).interior, Some(0));
    assert_eq!(m.interface(0).exterior, Some(1));
    assert_eq!(m.interface(1).interior, None);
    assert_eq!(m.interface(1).exterior, Some(0));
    assert_eq!(m.camera, None);
    assert!(matches!(l.integrator, Integrator::VolPath(_)));
}

#[test]
fn hg_defaults_to_g_0_8_and_the_sensor_takes_a_medium() {
    let xml = r#"<scene version="3.0.0">
  <integrator type="volpath"/>
  <medium type="homogeneous" id="m"><phase type="hg"/></medium>
  <sensor type="perspective"><ref id="m"/>
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  </sensor>
</scene>"#;
    let l = load_scene_str(xml, &scenes_dir().join("media-inputs.xml"), &[]).expect("loads");
    assert_eq!(l.scene.media.camera, Some(0));
    let Medium::Homogeneous(h) = &l.scene.media.media[0] else {
        panic!("not homogeneous")
    };
    assert_eq!(
        h.phase,
        PhaseFunction::Hg(tessera_core::medium::HenyeyGreenstein { g: 0.8 })
    );
}

#[test]
fn path_on_a_scene_with_media_names_volpath() {
    refused(
        SPHERE_WITH_MEDIUM,
        r#"<integrator type="path"/>"#,
        "\"volpath\"",
        2,
    );
    // Without an integrator element (the default is path): at the medium.
    refused(SPHERE_WITH_MEDIUM, "", "\"volpath\"", 7);
    // The command line's choice is refused as well.
    let mut l = load(SPHERE_WITH_MEDIUM, VOLPATH).expect("loads");
    let e = l.set_integrator(Some("path"), None).unwrap_err();
    assert!(e.contains("volpath"), "{e}");
    l.set_integrator(Some("volpath"), None).expect("volpath");
    // Control: the same scene with volpath loads, and path loads a scene without media.
    load(r#"<shape type="sphere"/>"#, r#"<integrator type="path"/>"#).expect("loads");
}

#[test]
fn unsupported_media_are_located_errors_naming_them() {
    refused(
        r#"<shape type="sphere"><bsdf type="null"/><medium type="homogeneous" name="interior">
    <volume name="sigma_t" type="gridvolume"><string name="filename" value="a.vol"/></volume>
  </medium></shape>"#,
        VOLPATH,
        "must be an rgb color (or a float), found volume \"gridvolume\"",
        7,
    );
    // Every phase function of Mitsuba 3 is read; a misspelt one is named with the known ones.
    refused(
        r#"<shape type="sphere"><medium type="homogeneous" name="interior"><phase type="sggxx"/></medium></shape>"#,
        VOLPATH,
        "\"sggxx\"",
        6,
    );
}

#[test]
fn volpathmis_reads_its_parameters() {
    use tessera_core::integrator::MediumMis;
    let read = |params: &str| {
        let l = load(
            SPHERE_WITH_MEDIUM,
            &format!(r#"<integrator type="volpathmis">{params}</integrator>"#),
        )
        .expect("loads");
        let Integrator::VolPath(v) = l.integrator else {
            panic!("not a volumetric path tracer")
        };
        v
    };
    let v = read("");
    assert_eq!(v.mis, MediumMis::Joint { spectral: true });
    assert_eq!((v.max_depth, v.rr_depth, v.hide_emitters), (None, 5, false));
    let v = read(
        r#"<boolean name="use_spectral_mis" value="false"/><integer name="max_depth" value="4"/>
        <integer name="rr_depth" value="2"/><boolean name="hide_emitters" value="true"/>"#,
    );
    assert_eq!(v.mis, MediumMis::Joint { spectral: false });
    assert_eq!(
        (v.max_depth, v.rr_depth, v.hide_emitters),
        (Some(4), 2, true)
    );
    refused(
        SPHERE_WITH_MEDIUM,
        r#"<integrator type="volpathmis"><float name="use_spectral_mis" value="1"/></integrator>"#,
        "\"use_spectral_mis\"",
        2,
    );
}

#[test]
fn bad_media_parameters_are_located_errors() {
    refused(
        r#"<shape type="sphere"><medium type="homogeneous" name="interior"><float name="sigma_t" value="-1"/></medium></shape>"#,
        VOLPATH,
        "\"sigma_t\"",
        6,
    );
    refused(
        r#"<shape type="sphere"><medium type="homogeneous" name="interior"><phase type="hg"><float name="g" value="1"/></phase></medium></shape>"#,
        VOLPATH,
        "\"g\"",
        6,
    );
    refused(
        r#"<shape type="sphere"><medium type="homogeneous" name="interior"><float name="density" value="1"/></medium></shape>"#,
        VOLPATH,
        "unused parameter \"density\"",
        6,
    );
    refused(
        r#"<shape type="sphere"><medium type="homogeneous"/></shape>"#,
        VOLPATH,
        "needs name=\"interior\" or name=\"exterior\"",
        6,
    );
    refused(
        r#"<bsdf type="diffuse" id="d"/><shape type="sphere"><ref name="interior" id="d"/></shape>"#,
        VOLPATH,
        "must be a <medium>",
        6,
    );
    refused(
        r#"<shape type="sphere"><medium type="homogeneous" name="interior"><phase type="isotropic"/>
    <phase type="isotropic"/></medium></shape>"#,
        VOLPATH,
        "more than one phase function",
        7,
    );
}

/// A homogeneous medium in a sphere holding `phase`, for the phase function refusals.
fn with_phase(phase: &str) -> String {
    format!(
        r#"<shape type="sphere"><medium type="homogeneous" name="interior">{phase}</medium></shape>"#
    )
}

#[test]
fn bad_phase_functions_are_located_errors() {
    let tab = |v: &str| {
        with_phase(&format!(
            r#"<phase type="tabphase"><string name="values" value="{v}"/></phase>"#
        ))
    };
    refused(&tab("1"), VOLPATH, "needs at least two numbers, found 1", 6);
    refused(
        &tab("1, -1, 2"),
        VOLPATH,
        "must be finite and non-negative, found -1 (entry 2)",
        6,
    );
    refused(&tab("0, 0"), VOLPATH, "are all zero", 6);
    refused(&tab("1, 2, x"), VOLPATH, "\"x\" is not a number", 6);
    refused(
        &with_phase(r#"<phase type="tabphase"/>"#),
        VOLPATH,
        "\"values\"",
        6,
    );
    refused(
        &with_phase(r#"<phase type="tabphase"><float name="values" value="1"/></phase>"#),
        VOLPATH,
        "\"values\"",
        6,
    );
    let blend = |inner: &str| with_phase(&format!(r#"<phase type="blendphase">{inner}</phase>"#));
    let two = r#"<phase type="isotropic"/><phase type="rayleigh"/>"#;
    refused(&blend(two), VOLPATH, "\"weight\"", 6);
    refused(
        &blend(&format!(r#"<float name="weight" value="1.5"/>{two}"#)),
        VOLPATH,
        "must be in [0, 1], found 1.5",
        6,
    );
    refused(
        &blend(r#"<float name="weight" value="0.5"/><phase type="isotropic"/>"#),
        VOLPATH,
        "needs exactly two nested phase functions, found 1",
        6,
    );
    refused(
        &blend(&format!(
            r#"<float name="weight" value="0.5"/>{two}<phase type="isotropic"/>"#
        )),
        VOLPATH,
        "needs exactly two nested phase functions, found 3",
        6,
    );
    refused(
        &blend(&format!(
            r#"<volume type="gridvolume" name="weight"><string name="filename" value="media/smoke.vol"/></volume>{two}"#
        )),
        VOLPATH,
        "must be the same everywhere",
        6,
    );
}

#[test]
fn blendphase_reads_a_constant_volume_and_file_order() {
    let body = with_phase(
        r#"<phase type="blendphase"><volume type="constvolume" name="weight"><float name="value" value="0.25"/></volume>
        <phase type="rayleigh"/><phase type="isotropic"/></phase>"#,
    );
    let l = load(&body, VOLPATH).expect("loads");
    let PhaseFunction::Blend(b) = &*l.scene.media.media[0].phase_at(glam::Vec3::ZERO) else {
        panic!("not a blend")
    };
    assert_eq!(b.weight, 0.25);
    assert!(matches!(*b.first, PhaseFunction::Rayleigh(_)), "{b:?}");
    assert!(matches!(*b.second, PhaseFunction::Isotropic(_)), "{b:?}");
}

#[test]
fn has_spectral_extinction_is_one_located_warning() {
    let body = r#"<shape type="sphere"><bsdf type="null"/>
    <medium type="homogeneous" name="interior"><boolean name="has_spectral_extinction" value="false"/></medium>
  </shape>"#;
    let l = load(body, VOLPATH).expect("loads");
    let w: Vec<&String> = l
        .warnings
        .iter()
        .filter(|w| w.contains("has_spectral_extinction"))
        .collect();
    assert_eq!(w.len(), 1, "{:?}", l.warnings);
    assert!(w[0].contains("media-inputs.xml:7:"), "{}", w[0]);
    // Control: without it, no warning.
    let l = load(SPHERE_WITH_MEDIUM, VOLPATH).expect("loads");
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
}

/// `--stats` counts medium events: a sphere of medium (sigma_t 2) bounded by `null` under a
/// sky, seen by a 4x4 camera, has scatterings, passes and null crossings (of paths and of shadow
/// rays); the same scene without its medium has none of them.
#[test]
fn probe_counts_medium_events() {
    use tessera::render::RenderOptions;
    use tessera::render_stats::render_with_stats;
    use tessera_core::render::RenderJob;
    let count = |body: &str| {
        let xml = format!(
            r#"<scene version="3.0.0"><integrator type="volpath"/>
  <sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  </sensor>
  <emitter type="constant"/>
  {body}
</scene>"#
        );
        let l = load_scene_str(&xml, &scenes_dir().join("media-inputs.xml"), &[]).expect("loads");
        let job = RenderJob::new(&l.scene, &l.integrator, 1);
        let opts = RenderOptions {
            threads: 1,
            ..Default::default()
        };
        render_with_stats(&job, 0..64, &opts, &mut |_, _| {}).1
    };
    let c = count(SPHERE_WITH_MEDIUM);
    println!("{c:?}");
    assert!(c.medium_scatters > 0 && c.medium_passes > 0, "{c:?}");
    assert!(c.null_crossings > 0 && c.shadow_null_crossings > 0, "{c:?}");
    // Control: a diffuse sphere without media counts none of them.
    let c = count(r#"<shape type="sphere"/>"#);
    assert_eq!(
        (
            c.medium_scatters,
            c.medium_passes,
            c.null_crossings,
            c.shadow_null_crossings
        ),
        (0, 0, 0, 0)
    );
    assert!(c.continuation_rays > 0);
}

/// `sggx <phase>` text with `S` read from `file` (relative to `scenes/`).
fn sggx_from(file: &str) -> String {
    format!(
        r#"<phase type="sggx"><volume type="gridvolume" name="S"><string name="filename" value="{file}"/></volume></phase>"#
    )
}

#[test]
fn sggx_loads_fixed_or_varying_and_a_homogeneous_albedo_may_be_a_grid() {
    // One voxel: a fixed function, also in a homogeneous medium.
    let l = load(&with_phase(&sggx_from("media/flakes_uniform.vol")), VOLPATH).expect("loads");
    let p = l.scene.media.media[0]
        .phase_at(glam::Vec3::ZERO)
        .into_owned();
    assert!(matches!(p, PhaseFunction::Sggx(_)), "{p:?}");
    // A grid that varies: the heterogeneous medium looks it up where it scatters.
    let body = format!(
        r#"<shape type="sphere"><medium type="heterogeneous" name="interior">{}</medium></shape>"#,
        sggx_from("media/flakes.vol")
    );
    let l = load(&body, VOLPATH).expect("loads");
    let Medium::Heterogeneous(h) = &l.scene.media.media[0] else {
        panic!("not heterogeneous")
    };
    let (a, b) = (glam::Vec3::splat(0.1), glam::Vec3::new(0.9, 0.5, 0.5));
    assert_ne!(
        h.phase.at(a),
        h.phase.at(b),
        "the matrix varies through the grid"
    );
    // A homogeneous medium's albedo from a grid, looked up in place.
    let body = r#"<shape type="sphere"><medium type="homogeneous" name="interior">
      <volume type="gridvolume" name="albedo"><string name="filename" value="media/smoke.vol"/></volume>
    </medium></shape>"#;
    let l = load(body, VOLPATH).expect("loads");
    let Medium::Homogeneous(m) = &l.scene.media.media[0] else {
        panic!("not homogeneous")
    };
    let (lo, hi) = (
        m.albedo.eval(glam::Vec3::splat(0.02)),
        m.albedo.eval(glam::Vec3::new(0.5, 0.3, 0.5)),
    );
    assert!(hi.x > lo.x, "albedo {lo} at the grid's corner, {hi} inside");
}

#[test]
fn bad_sggx_phases_are_located_errors() {
    refused(
        &with_phase(&sggx_from("media/flakes.vol")),
        VOLPATH,
        "whose S varies through space, which would make its extinction vary: use a \
         heterogeneous medium",
        6,
    );
    refused(
        &with_phase(r#"<phase type="sggx"/>"#),
        VOLPATH,
        "missing parameter \"S\"",
        6,
    );
    refused(
        &with_phase(r#"<phase type="sggx"><float name="S" value="1"/></phase>"#),
        VOLPATH,
        "must be a gridvolume of 6 channels, not a value",
        6,
    );
    refused(
        &with_phase(&sggx_from("media/smoke.vol")),
        VOLPATH,
        "has 1 channel(s) per voxel: it needs 6",
        6,
    );
    refused(
        &with_phase(
            r#"<phase type="sggx"><volume type="constvolume" name="S"><float name="value" value="1"/></volume></phase>"#,
        ),
        VOLPATH,
        "is a constant: it must be a gridvolume of 6 channels",
        6,
    );
    // A matrix that is not positive definite (S_xx negative).
    let dir = std::env::temp_dir().join(format!("tessera-sggx-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("bad.vol");
    let mut b = b"VOL\x03".to_vec();
    for v in [1i32, 1, 1, 1, 6] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for v in [
        0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0, -1.0, 1.0, 1.0, 0.0, 0.0, 0.0,
    ] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    std::fs::write(&bad, b).expect("write");
    refused(
        &with_phase(&sggx_from(&bad.display().to_string())),
        VOLPATH,
        "the matrix of voxel (0, 0, 0)",
        6,
    );
    // A varying grid nested in a blend: no place to look it up at.
    let body = format!(
        r#"<shape type="sphere"><medium type="heterogeneous" name="interior"><phase type="blendphase"><float name="weight" value="0.5"/><phase type="isotropic"/>{}</phase></medium></shape>"#,
        sggx_from("media/flakes.vol")
    );
    refused(&body, VOLPATH, "only a medium's own phase function may", 6);
    // A 6-channel grid where 1 or 3 are meant.
    let body = r#"<shape type="sphere"><medium type="heterogeneous" name="interior"><volume type="gridvolume" name="sigma_t"><string name="filename" value="media/flakes.vol"/></volume></medium></shape>"#;
    refused(
        body,
        VOLPATH,
        "takes a volume of 1 or 3 channels, found 6",
        6,
    );
}

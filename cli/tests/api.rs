//! The library entry points (`tessera::load`, `load_str`, `render`): they render what the lower
//! level renders, the same bits for any thread count, and report bad input as located errors.
use std::path::Path;
use tessera::render::RenderOptions;

const SCENE: &str = r#"<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="24"/><integer name="height" value="16"/>
        </film>
    </sensor>
    <shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>"#;

fn bits(img: &tessera::Image) -> Vec<u32> {
    img.data.iter().flatten().map(|v| v.to_bits()).collect()
}

#[test]
fn render_from_a_string_matches_the_tile_renderer_for_any_thread_count() {
    let scene = tessera::load_str(SCENE, ".").expect("the scene loads");
    let one = tessera::render(
        &scene,
        &tessera::Options {
            threads: Some(1),
            ..Default::default()
        },
    );
    let two = tessera::render(
        &scene,
        &tessera::Options {
            threads: Some(2),
            tile_size: 5,
            ..Default::default()
        },
    );
    assert_eq!((one.width, one.height), (24, 16));
    assert_eq!(bits(&one), bits(&two));

    let job = tessera_core::render::RenderJob::new(&scene.scene, &scene.integrator, 0);
    let fb = tessera::render::render(
        &job,
        0..8,
        &RenderOptions {
            threads: 1,
            tile_size: 32,
            ..Default::default()
        },
        &mut |_, _| {},
    );
    let low: Vec<u32> = fb.rgb().iter().flatten().map(|v| v.to_bits()).collect();
    assert_eq!(bits(&one), low, "the scene's spp and seed are the defaults");

    // Control: another seed gives other bits.
    let other = tessera::render(
        &scene,
        &tessera::Options {
            seed: Some(1),
            ..Default::default()
        },
    );
    assert_ne!(bits(&one), bits(&other));
}

#[test]
fn load_reads_a_scene_file_and_reports_bad_input_with_its_location() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/furnace.xml");
    let scene = tessera::load(&path).expect("the furnace loads");
    assert_eq!(scene.spp, 64);

    let bad = SCENE.replace(
        "<rgb name=\"reflectance\" value=\"0.5\"/>",
        "<rgb name=\"reflectance\" value=\"x\"/>",
    );
    let err = tessera::load_str(&bad, ".")
        .expect_err("a bad colour is an error")
        .to_string();
    assert!(err.contains("<string>.xml:11:71:"), "{err}");
}

//! The Nori / Wakame dialect and Mitsuba 3's vocabulary describe the same scene: one file of
//! each, written for the same scene, render the same bits. (The camera blocks are written out
//! in each dialect; the objects come from one template filled with each dialect's words.)
use tessera_tests::{load_xml, render_loaded};

/// The objects of the test scene in a dialect's words: the shape tag, the transform's name, the
/// colour tag and the diffuse colour's name.
fn objects(shape: &str, to_world: &str, color: &str, albedo: &str) -> String {
    format!(
        r#"  <{shape} type="obj">
    <string name="filename" value="meshes/cbox_floor.obj"/>
    <transform name="{to_world}"><scale value="0.002"/><translate x="-0.5" y="0" z="-0.5"/></transform>
    <bsdf type="diffuse"><{color} name="{albedo}" value="0.6, 0.5, 0.4"/></bsdf>
  </{shape}>
  <{shape} type="sphere">
    <point name="center" value="0, 0.6, 0"/>
    <float name="radius" value="0.5"/>
    <bsdf type="diffuse"><{color} name="{albedo}" value="0.2, 0.7, 0.3"/></bsdf>
  </{shape}>
  <{shape} type="sphere">
    <point name="center" value="1, 2, 1"/>
    <float name="radius" value="0.3"/>
    <emitter type="area"><{color} name="radiance" value="8, 8, 6"/></emitter>
  </{shape}>
"#
    )
}

/// The test scene in Nori's dialect.
fn nori() -> String {
    let camera = r#"<scene>
  <integrator type="path_mis"/>
  <sampler type="independent"><integer name="sampleCount" value="8"/></sampler>
  <camera type="perspective">
    <transform name="toWorld"><lookat origin="0, 1, 6" target="0, 0.5, 0" up="0, 1, 0"/></transform>
    <float name="fov" value="35"/>
    <float name="nearClip" value="0.01"/> <!-- Nori's default is 1e-4, Mitsuba's 0.01 -->
    <integer name="width" value="24"/>
    <integer name="height" value="16"/>
    <rfilter type="gaussian"/>
  </camera>
"#;
    format!(
        "{camera}{}</scene>",
        objects("mesh", "toWorld", "color", "albedo")
    )
}

/// The test scene in Mitsuba 3's vocabulary.
fn mitsuba() -> String {
    let sensor = r#"<scene version="3.0.0">
  <integrator type="path"/>
  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0, 1, 6" target="0, 0.5, 0" up="0, 1, 0"/></transform>
    <float name="fov" value="35"/>
    <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
    <film type="hdrfilm">
      <integer name="width" value="24"/>
      <integer name="height" value="16"/>
      <rfilter type="gaussian"/>
    </film>
  </sensor>
"#;
    format!(
        "{sensor}{}</scene>",
        objects("shape", "to_world", "rgb", "reflectance")
    )
}

#[test]
fn nori_and_mitsuba_dialects_render_the_same_bits() {
    let nori = load_xml(&nori(), &[]);
    let mitsuba = load_xml(&mitsuba(), &[]);
    assert_eq!(nori.spp, 8);
    assert_eq!(
        (nori.scene.camera.width, nori.scene.camera.height),
        (24, 16)
    );
    let a = render_loaded(&nori, nori.spp, 3);
    let b = render_loaded(&mitsuba, mitsuba.spp, 3);
    assert!(
        a.pixels.iter().any(|p| p.sum[1] > 0.0),
        "the test scene renders black"
    );
    assert_eq!(a, b);
}

/// A PLY quad and the same quad as OBJ (both fan-triangulated the same way) render the same bits.
#[test]
fn ply_and_obj_meshes_load_alike() {
    let dir = std::env::temp_dir().join(format!("tessera-ply-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("quad.ply"),
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n\
         -1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n4 0 1 2 3\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("quad.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n",
    )
    .unwrap();
    let scene = |file: &str| {
        format!(
            r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="60"/>
    <transform name="to_world"><lookat origin="0.3, 0.2, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="12"/></film></sensor>
  <shape type="{}"><string name="filename" value="{}"/>
    <emitter type="area"><rgb name="radiance" value="1, 2, 3"/></emitter></shape>
  <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
</scene>"#,
            &file[file.len() - 3..],
            dir.join(file).display()
        )
    };
    let a = load_xml(&scene("quad.ply"), &[]);
    let b = load_xml(&scene("quad.obj"), &[]);
    let (fa, fb) = (render_loaded(&a, 4, 1), render_loaded(&b, 4, 1));
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        fa.pixels.iter().any(|p| p.sum[2] > p.sum[0]),
        "the quad is not visible"
    );
    assert_eq!(fa, fb);
}

/// `hide_emitters` hides what the camera sees directly (an area light, the environment) and
/// nothing else: light reflected off a surface is the same with or without it. (Mitsuba 3,
/// measured: a camera ray meeting an emitter gives 0 even where the emitter's BSDF reflects.)
#[test]
fn hide_emitters_hides_only_what_the_camera_sees_directly() {
    let xml = |hide: bool| {
        format!(
            r#"<scene version="3.0.0">
  <integrator type="path"><boolean name="hide_emitters" value="{hide}"/></integrator>
  <sensor type="perspective"><float name="fov" value="60"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/><rfilter type="box"/></film></sensor>
  <shape type="sphere"><point name="center" value="-1, 0, 0"/><float name="radius" value="0.6"/>
    <bsdf type="diffuse"/><emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>
  <shape type="sphere"><point name="center" value="1, 0, 0"/><float name="radius" value="0.6"/></shape>
  <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
</scene>"#
        )
    };
    let shown = render_loaded(&load_xml(&xml(false), &[]), 16, 5);
    let hidden = render_loaded(&load_xml(&xml(true), &[]), 16, 5);
    let (light, diffuse, sky) = ((3, 8), (12, 8), (8, 1));
    assert!(shown.at(light.0, light.1).sum[0] > 0.0 && shown.at(sky.0, sky.1).sum[0] > 0.0);
    assert_eq!(
        hidden.at(light.0, light.1).sum,
        [0.0; 3],
        "the light is still visible"
    );
    assert_eq!(
        hidden.at(sky.0, sky.1).sum,
        [0.0; 3],
        "the environment is still visible"
    );
    assert!(
        hidden.at(diffuse.0, diffuse.1).sum[0] > 0.0,
        "reflected light vanished"
    );
    assert_eq!(
        hidden.at(diffuse.0, diffuse.1),
        shown.at(diffuse.0, diffuse.1),
        "reflected light changed"
    );
}

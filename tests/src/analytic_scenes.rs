//! Scenes with closed-form answers, shared by the analytic t-tests (`analytic.rs`,
//! `emitters_analytic.rs`, `course_integrators.rs`), the sampler tests
//! (`sampler_zsobol_render.rs`) and the stress tests, built from one camera block and one lit
//! plane or square.

/// The integrators that sample lights directly, so they find a delta light (point, spot,
/// directional); `path_mats` and `direct_mats` sample only the BSDF and never do.
pub const LIGHT_SAMPLING_INTEGRATORS: [&str; 6] = [
    "path_ems",
    "path_half",
    "path_mis",
    "direct_ems",
    "direct_mis",
    "direct",
];

/// A scene of a perspective camera (field of view `fov` degrees, `lookat` the attributes of a
/// `<lookat>` tag, a box-filtered `res x res` film) and the XML elements in `body`.
pub fn scene(fov: f64, lookat: &str, res: u32, body: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="{fov}"/>
    <transform name="to_world"><lookat {lookat}/></transform>
    <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/><rfilter type="box"/></film>
  </sensor>
{body}
</scene>"#
    )
}

/// A 1x1 view (field of view 0.001 degrees, box filter) from the `<lookat>` attributes
/// `lookat` of a 20 x 20 diffuse square at z = 0 (reflectance 0.7, 0.5, 0.3), with `head`
/// (integrator, defaults) before the sensor and `body` (lights, occluders) after the square.
pub fn one_pixel_over_square(head: &str, lookat: &str, body: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  {head}
  <sensor type="perspective">
    <float name="fov" value="0.001"/>
    <transform name="to_world"><lookat {lookat}/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>
  </shape>
  {body}
</scene>"#
    )
}

/// A large diffuse plane at z = 0 (reflectance 0.7, 0.5, 0.3) lit by the elements in `light`;
/// a 1x1 camera with a tiny field of view looks at the origin from (5, 0, 2).
pub fn over_diffuse_plane(light: &str) -> String {
    let body = format!(
        r#"  <shape type="rectangle">
    <transform name="to_world"><scale value="1000"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>
  </shape>
{light}"#
    );
    scene(
        0.001,
        r#"origin="5, 0, 2" target="0, 0, 0" up="0, 0, 1""#,
        1,
        &body,
    )
}

/// The diffuse plane of [`over_diffuse_plane`] lit by a sphere light (radius 0.5, radiance 10)
/// 3 above the point the camera sees.
pub fn sphere_light() -> String {
    over_diffuse_plane(
        r#"  <shape type="sphere">
    <point name="center" value="0, 0, 3"/>
    <float name="radius" value="0.5"/>
    <emitter type="area"><rgb name="radiance" value="10"/></emitter>
  </shape>"#,
    )
}

/// An inward-facing emitting diffuse `shape` (radiance 1, reflectance 0.3, 0.5, 0.7) with the
/// extra parameters `params`: the radiance inside is 1 / (1 - albedo) with unbounded depth.
fn closed_emitter(shape: &str, params: &str) -> String {
    format!(
        r#"  <shape type="{shape}">{params}
    <boolean name="flip_normals" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter>
  </shape>"#
    )
}

/// A closed emitting sphere of radius 2 (`closed_emitter`) seen from its centre through a
/// `res x res` film with field of view `fov`.
pub fn closed_sphere(fov: f64, res: u32) -> String {
    let body = closed_emitter("sphere", "\n    <float name=\"radius\" value=\"2\"/>");
    scene(
        fov,
        r#"origin="0, 0, 0" target="0, 0, 1" up="0, 1, 0""#,
        res,
        &body,
    )
}

/// A closed emitting cube (a triangle mesh, `closed_emitter`) seen from inside.
pub fn furnace_box() -> String {
    let lookat = r#"origin="0.1, 0.2, 0" target="1, 0.3, 0.4" up="0, 1, 0""#;
    scene(1.0, lookat, 1, &closed_emitter("cube", ""))
}

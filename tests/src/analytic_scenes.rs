//! Scene files with closed-form answers, shared by the analytic t-tests and the sampler tests.

/// A diffuse plane (reflectance 0.7, 0.5, 0.3) lit by a sphere light (radius 0.5, radiance 10)
/// 3 above it; the camera looks straight at the point below the light.
pub const SPHERE_LIGHT: &str = r#"<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="0.001"/>
    <transform name="to_world"><lookat origin="5, 0, 2" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="1000"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>
  </shape>
  <shape type="sphere">
    <point name="center" value="0, 0, 3"/>
    <float name="radius" value="0.5"/>
    <emitter type="area"><rgb name="radiance" value="10"/></emitter>
  </shape>
</scene>"#;

/// A closed, inward-facing emitting cube (radiance 1, reflectance 0.3, 0.5, 0.7) seen from
/// inside: the radiance is 1 / (1 - albedo) with unbounded depth.
pub const FURNACE_BOX: &str = r#"<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="1"/>
    <transform name="to_world"><lookat origin="0.1, 0.2, 0" target="1, 0.3, 0.4" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
  <shape type="cube">
    <boolean name="flip_normals" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter>
  </shape>
</scene>"#;

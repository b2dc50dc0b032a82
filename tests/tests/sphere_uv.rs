//! Texture coordinates are computed only where something reads them: a sphere hit in
//! `Scene::intersect` carries zero `uv` where neither its BSDF (nested models and bump maps
//! included) nor its area emitter reads coordinates, and `Scene::intersect_full` computes them
//! everywhere. Everything else of the interaction is the same bits either way; every sphere
//! whose material or light varies over its surface, and every other shape, keeps its `uv`.
//! Control: the two casts do differ in `uv` on the plain spheres (the coordinates are not zero
//! there), so the comparison can fail.
use tessera_core::glam::Vec3;
use tessera_core::math::Ray;
use tessera_tests::load_xml;

const SCENE: &str = r#"<scene version="3.0.0">
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
    <integer name="height" value="8"/></film></sensor>
  <shape type="sphere"><point name="center" x="-6" y="0" z="0"/>
    <bsdf type="diffuse"/></shape>
  <shape type="sphere"><point name="center" x="-3" y="0" z="0"/>
    <bsdf type="twosided"><bsdf type="roughconductor"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0" y="0" z="0"/>
    <bsdf type="diffuse"><texture type="checkerboard" name="reflectance"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="3" y="0" z="0"/>
    <bsdf type="blendbsdf"><texture type="checkerboard" name="weight"/>
      <bsdf type="diffuse"/><bsdf type="conductor"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="6" y="0" z="0"/>
    <emitter type="area"><texture type="checkerboard" name="radiance"/></emitter></shape>
  <shape type="rectangle"><transform name="to_world"><translate x="9"/></transform></shape>
</scene>"#;

#[test]
fn computed_where_read() {
    let loaded = load_xml(SCENE, &[]);
    let scene = &loaded.scene;
    // Left to right: plain, plain (nested), textured, textured weight, textured light, a mesh.
    let expect = [false, false, true, true, true, true];
    let mut differed = 0;
    for (k, x) in [-6.0f32, -3.0, 0.0, 3.0, 6.0, 9.0].into_iter().enumerate() {
        for (dx, dy) in [(0.1, 0.2), (-0.3, 0.45), (0.6, -0.5)] {
            let ray = Ray::new(Vec3::new(x + dx, dy, 5.0), Vec3::new(0.0, 0.0, -1.0));
            let fast = scene.intersect(&ray).expect("hits the shape in front");
            let full = scene.intersect_full(&ray).expect("hits the shape in front");
            assert_eq!(scene.reads_uv(fast.shape), expect[k], "shape at x = {x}");
            assert_eq!((fast.p, fast.t, fast.ng), (full.p, full.t, full.ng));
            assert_eq!((fast.frame.s, fast.frame.n), (full.frame.s, full.frame.n));
            assert_eq!((fast.shape, fast.wi), (full.shape, full.wi));
            assert!(full.uv.x > 0.0 && full.uv.y > 0.0, "{:?}", full.uv);
            if expect[k] {
                assert_eq!(fast.uv, full.uv);
            } else {
                assert_eq!(fast.uv, tessera_core::glam::Vec2::ZERO);
                differed += 1;
            }
        }
    }
    assert_eq!(differed, 6);
}

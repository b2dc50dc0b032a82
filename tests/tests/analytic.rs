//! Rendered values against closed-form answers, by Student's t-test on the samples of one pixel.
//!
//! Each case renders a 1x1 image through a tiny field of view and tests the pixel's sample mean
//! against the analytic radiance at significance 0.01, Sidak-corrected over every test in this
//! file, for every integrator that can handle the case (one that cannot, such as BSDF sampling
//! with a point light, must give exactly zero). A control shows the test rejects a reference 1%
//! off.
use tessera_core::glam::{DMat4, DVec3};
use tessera_core::math::Norm;
use tessera_lab::stats::{sidak_alpha, t_test_from_sums};
use tessera_tests::analytic_scenes::{
    self as scenes, closed_sphere, over_diffuse_plane, sphere_light, LIGHT_SAMPLING_INTEGRATORS,
};
use tessera_tests::{load_xml, render_loaded};

/// Path tracers (take max_depth) and direct-lighting integrators (one bounce).
const PATHS: [&str; 4] = ["path_mats", "path_ems", "path_half", "path_mis"];
const DIRECTS: [&str; 4] = ["direct_ems", "direct_mats", "direct_mis", "direct"];

/// Number of t-tests in this file (cases x integrators x channels), for the Sidak correction:
/// environment sphere 8, closed sphere 4 x 5 + 4, sphere light 8, point light 6, polygons 2 x 8,
/// furnace box 8.
const N_TESTS: usize = (8 + 24 + 8 + 6 + 16 + 8) * 3;

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// Loads `xml` and switches to integrator `name` (with `max_depth` for path tracers).
fn load_with(xml: &str, name: &str, max_depth: Option<i64>) -> tessera_scene::LoadedScene {
    let mut loaded = load_xml(xml, &[]);
    loaded
        .set_integrator(Some(name), max_depth)
        .expect("known integrator");
    loaded
}

/// Renders `xml` (a 1x1 image) and t-tests each channel against `expected`.
fn check(
    label: &str,
    xml: &str,
    integrator: &str,
    max_depth: Option<i64>,
    spp: u64,
    expected: [f64; 3],
) {
    let loaded = load_with(xml, integrator, max_depth);
    let fb = render_loaded(&loaded, spp, 7);
    let p = fb.at(0, 0);
    tessera_tests::assert_pixel_matches(label, p, expected, alpha());
}

/// A diffuse sphere (albedo 0.2, 0.5, 0.8) under a constant environment of radiance 1.5.
fn env_sphere() -> String {
    let body = r#"  <shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></shape>
  <emitter type="constant"><rgb name="radiance" value="1.5"/></emitter>"#;
    scenes::scene(
        1.0,
        r#"origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0""#,
        1,
        body,
    )
}

/// A convex diffuse object under a constant environment reflects albedo x radiance.
#[test]
fn diffuse_sphere_in_constant_environment() {
    for integ in PATHS.iter().chain(&DIRECTS) {
        check(
            &format!("env sphere {integ}"),
            &env_sphere(),
            integ,
            None,
            100_000,
            [0.3, 0.75, 1.2],
        );
    }
}

/// Inside a closed emitting diffuse sphere: Le (1 - a^d) / (1 - a) at max_depth d, Le / (1 - a)
/// unbounded; direct lighting gives Le (1 + a).
#[test]
fn inside_closed_emitting_sphere() {
    let albedo = [0.3f64, 0.5, 0.7];
    for depth in [1i32, 2, 3, 5, -1] {
        let expected = albedo.map(|a| {
            if depth < 0 {
                1.0 / (1.0 - a)
            } else {
                (1.0 - a.powi(depth)) / (1.0 - a)
            }
        });
        for integ in PATHS {
            check(
                &format!("closed sphere {integ} depth {depth}"),
                &closed_sphere(1.0, 1),
                integ,
                Some(depth as i64),
                100_000,
                expected,
            );
        }
    }
    for integ in DIRECTS {
        check(
            &format!("closed sphere {integ}"),
            &closed_sphere(1.0, 1),
            integ,
            None,
            100_000,
            albedo.map(|a| 1.0 + a),
        );
    }
}

/// [`check`] of a scene lit directly by an area light, with every integrator: the path tracers
/// at max_depth 2 (direct light only), BSDF sampling alone (`*_mats`) with `mats_spp` samples,
/// the others with 100,000.
fn check_direct_light(label: &str, xml: &str, mats_spp: u64, expected: [f64; 3]) {
    for integ in PATHS.iter().chain(&DIRECTS) {
        let spp = if integ.ends_with("mats") {
            mats_spp
        } else {
            100_000
        };
        let depth = integ.starts_with("path").then_some(2);
        check(
            &format!("{label} {integ}"),
            xml,
            integ,
            depth,
            spp,
            expected,
        );
    }
}

/// Directly below a sphere light of radius r at height h over a diffuse plane:
/// a L r^2 / h^2 (direct lighting only, max_depth 2).
#[test]
fn sphere_light_over_diffuse_plane() {
    let (l, r, h) = (10.0f64, 0.5f64, 3.0f64);
    let expected = [0.7f64, 0.5, 0.3].map(|a| a * l * r * r / (h * h));
    check_direct_light("sphere light", &sphere_light(), 2_000_000, expected);
}

/// The diffuse plane lit by a point light (intensity 20) 2 above the point the camera sees.
fn point_light() -> String {
    over_diffuse_plane(
        r#"  <emitter type="point">
    <point name="position" value="0, 0, 2"/>
    <rgb name="intensity" value="20"/>
  </emitter>"#,
    )
}

/// Directly below a point light of intensity I at height h over a diffuse plane:
/// a I / (pi h^2). BSDF sampling alone can never find a point light: exactly zero.
#[test]
fn point_light_over_diffuse_plane() {
    let (i, h) = (20.0f64, 2.0f64);
    let expected = [0.7f64, 0.5, 0.3].map(|a| a * i / (std::f64::consts::PI * h * h));
    for integ in LIGHT_SAMPLING_INTEGRATORS {
        let depth = integ.starts_with("path").then_some(2);
        check(
            &format!("point light {integ}"),
            &point_light(),
            integ,
            depth,
            100_000,
            expected,
        );
    }
    for integ in ["path_mats", "direct_mats"] {
        let fb = render_loaded(&load_with(&point_light(), integ, Some(2)), 10_000, 7);
        assert_eq!(fb.at(0, 0).sum, [0.0; 3], "{integ} found a point light");
    }
}

/// The test has power: the same render is rejected against a reference 1% off.
#[test]
fn control_rejects_a_wrong_reference() {
    let loaded = load_with(&sphere_light(), "path_mis", Some(2));
    let fb = render_loaded(&loaded, 100_000, 7);
    let p = fb.at(0, 0);
    let expected = 0.7 * 10.0 * 0.25 / 9.0 * 1.01;
    let t = t_test_from_sums(p.count as f64, p.sum[0], p.sum_sq[0], expected);
    assert!(!t.passes(alpha()), "a 1% wrong reference passed: {t}");
}

/// Irradiance at `x` (normal `n`) from a planar polygon of uniform radiance `l` seen from its
/// emitting side, by Lambert's formula: E = L/2 |sum_i theta_i (n . unit(v_i x v_i+1))|, with
/// v_i the vectors from x to the vertices and theta_i the angle between consecutive ones.
fn lambert_irradiance(x: DVec3, n: DVec3, vertices: &[DVec3], l: f64) -> f64 {
    let mut sum = 0.0;
    for i in 0..vertices.len() {
        let a = (vertices[i] - x).unit();
        let b = (vertices[(i + 1) % vertices.len()] - x).unit();
        let theta = a.dot(b).clamp(-1.0, 1.0).acos();
        sum += theta * n.dot(a.cross(b).unit());
    }
    0.5 * l * sum.abs()
}

fn polygon_scene(sx: f64, sy: f64, angle: f64, t: DVec3) -> (String, Vec<DVec3>) {
    let m = DMat4::from_translation(t)
        * DMat4::from_rotation_x(angle.to_radians())
        * DMat4::from_scale(DVec3::new(sx, sy, 1.0));
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| m.transform_point3(DVec3::new(x, y, 0.0)));
    let xml = over_diffuse_plane(&format!(
        r#"  <shape type="rectangle">
    <transform name="to_world">
      <scale x="{sx}" y="{sy}" z="1"/><rotate x="1" angle="{angle}"/><translate x="{}" y="{}" z="{}"/>
    </transform>
    <emitter type="area"><rgb name="radiance" value="5"/></emitter>
  </shape>"#,
        t.x, t.y, t.z
    ));
    (xml, corners.to_vec())
}

/// Rectangular emitters over a diffuse plane against Lambert's polygon formula (my own
/// calculator above): a / pi * E at the point the camera sees.
#[test]
fn polygonal_emitters_match_lamberts_formula() {
    let cases = [
        (0.8, 0.5, 150.0, DVec3::new(0.3, 0.2, 2.0)),
        (1.5, 1.0, 100.0, DVec3::new(-0.5, 1.5, 2.0)),
    ];
    for (k, (sx, sy, angle, t)) in cases.into_iter().enumerate() {
        let (xml, corners) = polygon_scene(sx, sy, angle, t);
        let e = lambert_irradiance(DVec3::ZERO, DVec3::Z, &corners, 5.0);
        assert!(
            e > 0.5,
            "case {k}: the light barely reaches the point (E = {e})"
        );
        let expected = [0.7f64, 0.5, 0.3].map(|a| a * e / std::f64::consts::PI);
        check_direct_light(&format!("polygon {k}"), &xml, 400_000, expected);
    }
}

/// A closed emitting diffuse box (a triangle mesh lit from inside): 1 / (1 - a) for path
/// tracers, 1 + a for direct lighting.
#[test]
fn furnace_box() {
    let albedo = [0.3f64, 0.5, 0.7];
    for integ in PATHS {
        check(
            &format!("furnace box {integ}"),
            &scenes::furnace_box(),
            integ,
            Some(-1),
            100_000,
            albedo.map(|a| 1.0 / (1.0 - a)),
        );
    }
    for integ in DIRECTS {
        check(
            &format!("furnace box {integ}"),
            &scenes::furnace_box(),
            integ,
            None,
            100_000,
            albedo.map(|a| 1.0 + a),
        );
    }
}

//! Rendered values against closed-form answers, by Student's t-test on the samples of one pixel.
//!
//! Each case renders a 1x1 image through a tiny field of view and tests the pixel's sample mean
//! against the analytic radiance at significance 0.01, Sidak-corrected over every test in this
//! file. A control shows the same test rejects a reference 1% off.
use statrs::distribution::{ContinuousCDF, StudentsT};
use tessera::stats::{sidak_alpha, t_test_from_sums};
use tessera_tests::{load_xml, render_loaded};

/// Number of t-tests in this file (cases x integrators x channels), for the Sidak correction.
const N_TESTS: usize = (3 + 15 + 3 + 2) * 3;
const INTEGRATORS: [&str; 3] = ["path_mats", "path_half", "path_mis"];

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// Renders `xml` (a 1x1 image) and t-tests each channel against `expected`.
fn check(label: &str, xml: &str, defines: &[(&str, &str)], spp: u64, expected: [f64; 3]) {
    let loaded = load_xml(xml, defines);
    let fb = render_loaded(&loaded, spp, 7);
    let p = fb.at(0, 0);
    assert_eq!(p.dropped, 0, "{label}: non-finite samples");
    for k in 0..3 {
        let (n, mean) = (p.count as f64, p.sum[k] / p.count as f64);
        let var = ((p.sum_sq[k] - n * mean * mean) / (n - 1.0)).max(0.0);
        // The renderer computes in f32: its answer carries a few ulps of rounding that no
        // number of samples removes. That floor joins the standard error, so near-zero-variance
        // estimators (BSDF sampling in a furnace) are held to f32 precision, not beyond it.
        let ulp = (expected[k] as f32).abs() as f64 * f32::EPSILON as f64;
        let se = (var / n + (4.0 * ulp).powi(2)).sqrt();
        let t = (mean - expected[k]) / se;
        let p_value = 2.0
            * StudentsT::new(0.0, 1.0, n - 1.0)
                .expect("dof > 0")
                .sf(t.abs());
        assert!(
            p_value >= alpha(),
            "{label} channel {k}: mean {mean} vs expected {} (t = {t:.3}, p = {p_value:.3e})",
            expected[k]
        );
    }
}

const ENV_SPHERE: &str = r#"<scene version="3.0.0">
  <default name="integrator" value="path_mis"/>
  <integrator type="$integrator"/>
  <sensor type="perspective">
    <float name="fov" value="1"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
  <shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></shape>
  <emitter type="constant"><rgb name="radiance" value="1.5"/></emitter>
</scene>"#;

/// A convex diffuse object under a constant environment reflects albedo x radiance.
#[test]
fn diffuse_sphere_in_constant_environment() {
    for integ in INTEGRATORS {
        check(
            &format!("env sphere {integ}"),
            ENV_SPHERE,
            &[("integrator", integ)],
            100_000,
            [0.3, 0.75, 1.2],
        );
    }
}

const CLOSED_SPHERE: &str = r#"<scene version="3.0.0">
  <default name="integrator" value="path_mis"/>
  <default name="max_depth" value="-1"/>
  <integrator type="$integrator"><integer name="max_depth" value="$max_depth"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="1"/>
    <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, 1" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
  <shape type="sphere">
    <float name="radius" value="2"/>
    <boolean name="flip_normals" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter>
  </shape>
</scene>"#;

/// Inside a closed emitting diffuse sphere: Le (1 - a^d) / (1 - a) at max_depth d, Le / (1 - a)
/// unbounded.
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
        for integ in INTEGRATORS {
            let d = depth.to_string();
            check(
                &format!("closed sphere {integ} depth {depth}"),
                CLOSED_SPHERE,
                &[("integrator", integ), ("max_depth", &d)],
                100_000,
                expected,
            );
        }
    }
}

const SPHERE_LIGHT: &str = r#"<scene version="3.0.0">
  <default name="integrator" value="path_mis"/>
  <integrator type="$integrator"><integer name="max_depth" value="2"/></integrator>
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

/// Directly below a sphere light of radius r at height h over a diffuse plane:
/// a L r^2 / h^2 (direct lighting only, max_depth 2).
#[test]
fn sphere_light_over_diffuse_plane() {
    let (l, r, h) = (10.0f64, 0.5f64, 3.0f64);
    let expected = [0.7f64, 0.5, 0.3].map(|a| a * l * r * r / (h * h));
    for integ in INTEGRATORS {
        let spp = if integ == "path_mats" {
            2_000_000
        } else {
            100_000
        };
        check(
            &format!("sphere light {integ}"),
            SPHERE_LIGHT,
            &[("integrator", integ)],
            spp,
            expected,
        );
    }
}

const POINT_LIGHT: &str = r#"<scene version="3.0.0">
  <default name="integrator" value="path_mis"/>
  <integrator type="$integrator"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="0.001"/>
    <transform name="to_world"><lookat origin="5, 0, 2" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="1000"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>
  </shape>
  <emitter type="point">
    <point name="position" value="0, 0, 2"/>
    <rgb name="intensity" value="20"/>
  </emitter>
</scene>"#;

/// Directly below a point light of intensity I at height h over a diffuse plane:
/// a I / (pi h^2). BSDF sampling alone can never find a point light: exactly zero.
#[test]
fn point_light_over_diffuse_plane() {
    let (i, h) = (20.0f64, 2.0f64);
    let expected = [0.7f64, 0.5, 0.3].map(|a| a * i / (std::f64::consts::PI * h * h));
    for integ in ["path_half", "path_mis"] {
        check(
            &format!("point light {integ}"),
            POINT_LIGHT,
            &[("integrator", integ)],
            100_000,
            expected,
        );
    }
    let loaded = load_xml(POINT_LIGHT, &[("integrator", "path_mats")]);
    let fb = render_loaded(&loaded, 10_000, 7);
    assert_eq!(fb.at(0, 0).sum, [0.0; 3], "path_mats found a point light");
}

/// The test has power: the same render is rejected against a reference 1% off.
#[test]
fn control_rejects_a_wrong_reference() {
    let loaded = load_xml(SPHERE_LIGHT, &[("integrator", "path_mis")]);
    let fb = render_loaded(&loaded, 100_000, 7);
    let p = fb.at(0, 0);
    let expected = 0.7 * 10.0 * 0.25 / 9.0 * 1.01;
    let t = t_test_from_sums(p.count as f64, p.sum[0], p.sum_sq[0], expected);
    assert!(!t.passes(alpha()), "a 1% wrong reference passed: {t}");
}

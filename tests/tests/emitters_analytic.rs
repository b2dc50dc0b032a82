//! The new lights rendered against closed-form answers, by Student's t-test on the samples of
//! one pixel (the pattern of `analytic.rs`).
//!
//! Each case renders a 1x1 image through a 0.001 degree field of view (box filter) looking at
//! the origin of a large diffuse plane (or at a diffuse sphere), with direct lighting only
//! (`max_depth` 2) unless said otherwise, and tests the pixel's mean per channel against the
//! analytic radiance at significance 0.01, Sidak-corrected over every test in this file. BSDF
//! sampling alone never finds a delta light: `path_mats` and `direct_mats` must give exactly 0. A
//! control shows that the test rejects a reference 1% off.
use std::f64::consts::PI;
use tessera::image_io::{write_image, RgbImage};
use tessera_lab::stats::{sidak_alpha, t_test_from_sums};
use tessera_tests::analytic_scenes::{one_pixel_over_square, LIGHT_SAMPLING_INTEGRATORS};
use tessera_tests::{load_xml, render_loaded};

/// Number of t-tests in this file (cases x integrators x channels), for the Sidak correction:
/// delta lights (spot 2 cases, directional 2) x 6 integrators, distant disk 4 cases x 8, the
/// distant disk of 180 degrees, a constant envmap and an envmap lit at its pole x 8, opposing
/// disks x 8; 3 channels.
const N_TESTS: usize = (4 * 6 + 4 * 8 + 3 * 8 + 8) * 3;
/// The integrators that can find lights that rays can hit: the path tracers (max_depth 2 in the
/// plane scenes) and the direct-lighting integrators.
const INTEGRATORS: [&str; 8] = [
    "path_mats",
    "path_ems",
    "path_half",
    "path_mis",
    "direct_ems",
    "direct_mats",
    "direct_mis",
    "direct",
];
const ALBEDO: [f64; 3] = [0.7, 0.5, 0.3];

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// Renders `xml` (a 1x1 image) and t-tests each channel against `expected`.
fn check(label: &str, xml: &str, defines: &[(&str, &str)], spp: u64, expected: [f64; 3]) {
    // The file names path_mis (with its max_depth); switch by name, keeping that depth.
    let integ = defines
        .iter()
        .find(|(k, _)| *k == "integrator")
        .map(|(_, v)| *v);
    let others: Vec<(&str, &str)> = defines
        .iter()
        .copied()
        .filter(|(k, _)| *k != "integrator")
        .collect();
    let mut loaded = load_xml(xml, &others);
    loaded
        .set_integrator(integ, None)
        .expect("known integrator");
    let fb = render_loaded(&loaded, spp, 7);
    let p = fb.at(0, 0);
    tessera_tests::assert_pixel_matches(label, p, expected, alpha());
}

/// A diffuse square (z = 0, normal +z, albedo [`ALBEDO`], 20 wide: only its centre is lit in
/// these tests, and a small square keeps the hit point exact to f32 precision, which a steep
/// falloff would notice) seen at its origin from (5, 0, 2), with `lights` added.
fn plane_scene(lights: &str) -> String {
    one_pixel_over_square(
        r#"<default name="integrator" value="path_mis"/>
  <integrator type="$integrator"><integer name="max_depth" value="2"/></integrator>"#,
        r#"origin="5, 0, 2" target="0, 0, 0" up="0, 0, 1""#,
        lights,
    )
}

/// A diffuse sphere (albedo 0.2, 0.5, 0.8) seen from (0, 0, 5), with `lights` added; unbounded
/// depth (a convex object: one bounce is all there is).
fn sphere_scene(lights: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <default name="integrator" value="path_mis"/>
  <integrator type="$integrator"/>
  <sensor type="perspective">
    <float name="fov" value="0.001"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
  <shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></shape>
  {lights}
</scene>"#
    )
}

/// Samples for `integ` on a distant disk scene: `slow` for the integrators that reach the disk
/// only (or half the time) by BSDF sampling, 200,000 for the others.
fn spp_for(integ: &str, slow: u64) -> u64 {
    if integ.ends_with("mats") || integ == "path_half" {
        slow
    } else {
        200_000
    }
}

/// [`check`] with every integrator of [`INTEGRATORS`] (label `"{label} {integrator}"`), each
/// with `spp(integrator)` samples.
fn check_all_integrators(label: &str, xml: &str, spp: impl Fn(&str) -> u64, expected: [f64; 3]) {
    for integ in INTEGRATORS {
        check(
            &format!("{label} {integ}"),
            xml,
            &[("integrator", integ)],
            spp(integ),
            expected,
        );
    }
}

/// Checks a delta-light scene with the two integrators that sample lights, and that BSDF
/// sampling alone gives exactly 0.
fn check_delta(label: &str, xml: &str, expected: [f64; 3]) {
    for integ in LIGHT_SAMPLING_INTEGRATORS {
        check(
            &format!("{label} {integ}"),
            xml,
            &[("integrator", integ)],
            10_000,
            expected,
        );
    }
    for integ in ["path_mats", "direct_mats"] {
        let mut loaded = load_xml(xml, &[]);
        loaded
            .set_integrator(Some(integ), None)
            .expect("known integrator");
        let fb = render_loaded(&loaded, 10_000, 7);
        assert_eq!(
            fb.at(0, 0).sum,
            [0.0; 3],
            "{label}: {integ} found a delta light"
        );
    }
}

/// A spot light of intensity I at height h straight above the viewed point, shining down:
/// a I / (pi h^2).
#[test]
fn spot_light_centre() {
    let (i, h) = (20.0f64, 2.0f64);
    let xml = plane_scene(
        r#"<emitter type="spot">
    <rgb name="intensity" value="20"/>
    <float name="cutoff_angle" value="25"/>
    <transform name="to_world"><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform>
  </emitter>"#,
    );
    check_delta("spot centre", &xml, ALBEDO.map(|a| a * i / (PI * h * h)));
}

/// The spot's axis points straight down from (x, 0, h) with x = h tan 35 deg: the viewed point is
/// 35 degrees off the axis, inside the falloff between the default beam width (3/4 of the 40
/// degree cutoff = 30) and the cutoff. Mitsuba 3's falloff is linear in the angle:
/// (40 - 35) / (40 - 30) = 1/2. Radiance a/pi I 1/2 cos(35) / d^2 with d = h / cos(35).
#[test]
fn spot_light_in_falloff() {
    let (i, h) = (20.0f64, 2.0f64);
    let c = 35f64.to_radians().cos();
    let x = h * 35f64.to_radians().tan();
    let xml = plane_scene(&format!(
        r#"<emitter type="spot">
    <rgb name="intensity" value="20"/>
    <float name="cutoff_angle" value="40"/>
    <transform name="to_world"><lookat origin="{x}, 0, 2" target="{x}, 0, 0" up="0, 1, 0"/></transform>
  </emitter>"#
    ));
    let expected = ALBEDO.map(|a| a / PI * i * 0.5 * c * c * c / (h * h));
    check_delta("spot falloff", &xml, expected);
}

/// Directional light of irradiance E arriving at 30 degrees from the normal (`direction`):
/// a E cos(30) / pi.
#[test]
fn directional_light_direction() {
    let e = 3.0f64;
    let a = 30f64.to_radians();
    let xml = plane_scene(&format!(
        r#"<emitter type="directional">
    <vector name="direction" value="{}, 0, {}"/>
    <rgb name="irradiance" value="3"/>
  </emitter>"#,
        a.sin(),
        -a.cos()
    ));
    check_delta(
        "directional (direction)",
        &xml,
        ALBEDO.map(|al| al * e * a.cos() / PI),
    );
}

/// Directional light along `to_world`'s +z: +z rotated 120 degrees about +y travels along
/// (sin 120, 0, cos 120), 60 degrees from the plane's normal: a E cos(60) / pi.
#[test]
fn directional_light_to_world() {
    let e = 3.0f64;
    let xml = plane_scene(
        r#"<emitter type="directional">
    <transform name="to_world"><rotate y="1" angle="120"/></transform>
    <rgb name="irradiance" value="3"/>
  </emitter>"#,
    );
    check_delta(
        "directional (to_world)",
        &xml,
        ALBEDO.map(|al| al * e * 0.5 / PI),
    );
}

/// A distant disk of radiance L and half angle thetaA centred on the plane's normal: irradiance
/// pi L sin^2(thetaA), radiance a L sin^2(thetaA); all four path integrators.
#[test]
fn distant_disk_over_plane() {
    let l = 2.0f64;
    for theta in [5.0f64, 30.0, 90.0] {
        let xml = plane_scene(&format!(
            r#"<emitter type="distantdisk">
    <rgb name="radiance" value="2"/>
    <float name="theta_a" value="{theta}"/>
  </emitter>"#
        ));
        let s2 = theta.to_radians().sin().powi(2);
        let slow = if theta < 10.0 { 1_000_000 } else { 200_000 };
        let spp = |integ: &str| spp_for(integ, slow);
        let label = format!("distantdisk {theta} deg");
        check_all_integrators(&label, &xml, spp, ALBEDO.map(|a| a * l * s2));
    }
}

/// Opposing disks under a distant disk: an opaque disk of radius 0.5 hangs 1.5 above the lit
/// point, facing it, and hides the middle of a distant disk of half angle 30 degrees, whose
/// centre is straight up. What is left is the ring between thetaB = atan(0.5 / 1.5) and
/// thetaA, of projected solid angle pi (sin^2 thetaA - sin^2 thetaB), so the radiance is
/// a L (sin^2 thetaA - sin^2 thetaB). The hanging disk's underside sees no light directly
/// (max_depth 2), so no interreflection adds to it.
#[test]
fn opposing_disks_under_a_distant_disk() {
    let l = 2.0f64;
    let xml = plane_scene(
        r#"<emitter type="distantdisk">
    <rgb name="radiance" value="2"/>
    <float name="theta_a" value="30"/>
  </emitter>
  <shape type="disk">
    <transform name="to_world">
      <scale value="0.5"/>
      <rotate x="1" angle="180"/>
      <translate z="1.5"/>
    </transform>
  </shape>"#,
    );
    let tb = (0.5f64 / 1.5).atan();
    let ring = 30f64.to_radians().sin().powi(2) - tb.sin().powi(2);
    let spp = |integ: &str| spp_for(integ, 600_000);
    let label = "opposing disks, distantdisk 30 deg";
    check_all_integrators(label, &xml, spp, ALBEDO.map(|a| a * l * ring));
}

/// A disk of half angle 20 degrees whose centre is 40 degrees from the normal, given in Nori's
/// names (`thetaA`, `toWorld`): a cap entirely above the horizon has projected solid angle
/// pi sin^2(thetaA) cos(40), so the radiance is a L sin^2(20) cos(40).
#[test]
fn distant_disk_tilted_nori_names() {
    let l = 2.0f64;
    let xml = plane_scene(
        r#"<emitter type="distantdisk">
    <rgb name="radiance" value="2"/>
    <float name="thetaA" value="20"/>
    <transform name="toWorld"><rotate y="1" angle="40"/></transform>
  </emitter>"#,
    );
    let expected =
        ALBEDO.map(|a| a * l * 20f64.to_radians().sin().powi(2) * 40f64.to_radians().cos());
    check_all_integrators("distantdisk tilted", &xml, |_| 200_000, expected);
}

/// At 180 degrees the distant disk is a constant environment: a diffuse sphere reflects
/// albedo x radiance.
#[test]
fn distant_disk_180_is_a_constant_environment() {
    let xml = sphere_scene(
        r#"<emitter type="distantdisk">
    <rgb name="radiance" value="1.5"/>
    <float name="theta_a" value="180"/>
  </emitter>"#,
    );
    check_all_integrators(
        "distantdisk 180 sphere",
        &xml,
        |_| 100_000,
        [0.3, 0.75, 1.2],
    );
}

/// An environment map of one colour (a 8x4 EXR written here) with `scale` and a rotation is a
/// constant environment: a diffuse sphere reflects albedo x colour x scale.
#[test]
fn constant_envmap_on_a_sphere() {
    let dir = std::env::temp_dir().join(format!("tessera-emitters-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("constant.exr");
    let img = RgbImage {
        width: 8,
        height: 4,
        data: vec![[0.5, 1.0, 2.0]; 32],
    };
    write_image(&path, &img).expect("write the map");
    let xml = sphere_scene(&format!(
        r#"<emitter type="envmap">
    <string name="filename" value="{}"/>
    <float name="scale" value="1.5"/>
    <transform name="to_world"><rotate x="1" angle="30"/></transform>
  </emitter>"#,
        path.display()
    ));
    check_all_integrators(
        "constant envmap sphere",
        &xml,
        |_| 100_000,
        [0.2 * 0.75, 0.5 * 1.5, 0.8 * 3.0],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// An 8x5 environment map black but for its top row (radiance c), turned so that its up (+y)
/// is the plane's normal (+z). The top row is the pole and row y sits at theta = y pi / 4, so
/// the bilinear radiance is c (1 - theta / a) within a = 45 degrees of the normal, and the
/// radiance of the plane is albedo * 2 c (sin^2(a)/2 + cos(2a)/4 - sin(2a)/(8a)). Emitter
/// sampling alone (path_ems) must reach all of it although the pole row has sin(theta) = 0.
#[test]
fn envmap_lit_at_its_pole_over_plane() {
    let dir = std::env::temp_dir().join(format!("tessera-emitters-pole-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("pole.pfm");
    let c = [1.0f32, 2.0, 3.0];
    let mut data = vec![[0.0f32; 3]; 40];
    data[..8].fill(c);
    write_image(
        &path,
        &RgbImage {
            width: 8,
            height: 5,
            data,
        },
    )
    .expect("write the map");
    let xml = plane_scene(&format!(
        r#"<emitter type="envmap">
    <string name="filename" value="{}"/>
    <transform name="to_world"><rotate x="1" angle="90"/></transform>
  </emitter>"#,
        path.display()
    ));
    let a = PI / 4.0;
    let k = 2.0 * (a.sin().powi(2) / 2.0 + (2.0 * a).cos() / 4.0 - (2.0 * a).sin() / (8.0 * a));
    let expected = [0, 1, 2].map(|i| ALBEDO[i] * k * f64::from(c[i]));
    check_all_integrators("envmap lit at its pole", &xml, |_| 200_000, expected);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The test has power: the distant disk render is rejected against a reference 1% off.
#[test]
fn control_rejects_a_wrong_reference() {
    let xml = plane_scene(
        r#"<emitter type="distantdisk">
    <rgb name="radiance" value="2"/>
    <float name="theta_a" value="30"/>
  </emitter>"#,
    );
    let loaded = load_xml(&xml, &[("integrator", "path_mis")]);
    let fb = render_loaded(&loaded, 200_000, 7);
    let p = fb.at(0, 0);
    let expected = 0.7 * 2.0 * 0.25 * 1.01;
    let t = t_test_from_sums(p.count as f64, p.sum[0], p.sum_sq[0], expected);
    assert!(!t.passes(alpha()), "a 1% wrong reference passed: {t}");
}

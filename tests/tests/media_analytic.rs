//! `volpath` against closed forms, by Student's t-test on the samples of one pixel (1x1 image,
//! field of view 0.001 degrees): Beer-Lambert through a purely absorbing slab bounded by `null`
//! surfaces, seen directly against a constant sky and crossed by a shadow ray toward a
//! directional light, with a different extinction per channel; and white furnaces (a sphere of
//! medium of albedo 1 bounded by `null` under a sky of radiance 1: every pixel is 1) with
//! isotropic, Henyey-Greenstein, chromatic-extinction and SGGX microflake media. Significance 0.01,
//! Sidak-corrected over the file; each case has a control (the same render against a reference
//! 1% off, or the slab against 5% more extinction) that must be rejected. `volpathmis_analytic.rs`
//! renders the same scenes with `volpathmis`.
use tessera_tests::pixel_ttest::{check_pixel, control_pixel as control};

/// t-tests in this file: 2 slabs + 5 furnaces, 3 channels each.
const N_TESTS: usize = 7 * 3;

pub(crate) const SIGMA: [f64; 3] = [0.2, 0.5, 0.9];
pub(crate) const THICKNESS: f64 = 1.5;

/// A 1x1 camera at `origin` looking at `target`, in the medium `camera_medium` (an id or "").
pub(crate) fn scene(origin: &str, target: &str, camera_medium: &str, body: &str) -> String {
    let medium_ref = if camera_medium.is_empty() {
        String::new()
    } else {
        format!(r#"<ref id="{camera_medium}"/>"#)
    };
    format!(
        r#"<scene version="3.0.0">
  <integrator type="volpath"/>
  <sensor type="perspective">
    <float name="fov" value="0.001"/>
    <transform name="to_world"><lookat origin="{origin}" target="{target}" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    {medium_ref}
  </sensor>
{body}
</scene>"#
    )
}

/// A slab `THICKNESS` thick between z = 1 and z = 1 + THICKNESS, 40 wide, absorbing only, with
/// extinction `SIGMA` (times `scale`), bounded by `null`.
pub(crate) fn slab(scale: f64) -> String {
    let half = THICKNESS / 2.0;
    format!(
        r#"<shape type="cube">
    <transform name="to_world"><scale x="20" y="20" z="{half}"/><translate z="{z}"/></transform>
    <bsdf type="null"/>
    <medium type="homogeneous" name="interior">
      <rgb name="sigma_t" value="{}, {}, {}"/>
      <float name="scale" value="{scale}"/>
      <float name="albedo" value="0"/>
    </medium>
  </shape>"#,
        SIGMA[0],
        SIGMA[1],
        SIGMA[2],
        z = 1.0 + half
    )
}

fn check(label: &str, xml: &str, spp: u64, expected: [f64; 3]) {
    check_pixel(label, xml, spp, expected, N_TESTS);
}

pub(crate) fn beer(scale: f64, path: f64) -> [f64; 3] {
    SIGMA.map(|s| (-s * scale * path).exp())
}

/// The slab seen from above against a constant sky of radiance 1 behind it.
pub(crate) fn slab_against_the_sky() -> String {
    let body = format!(
        r#"{}
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter>"#,
        slab(1.0)
    );
    scene("0, 0, 5", "0, 0, 0", "", &body)
}

/// A diffuse floor (albedo 0.5) at z = 0 lit straight down by a directional light of
/// irradiance 2: under a slab, only a shadow ray through it carries the light.
pub(crate) const LIT_FLOOR: &str = r#"
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
  </shape>
  <emitter type="directional">
    <vector name="direction" x="0" y="0" z="-1"/>
    <rgb name="irradiance" value="2"/>
  </emitter>"#;

/// The slab over [`LIT_FLOOR`], seen from below the slab.
pub(crate) fn slab_on_a_shadow_ray() -> String {
    let body = format!("{}{LIT_FLOOR}", slab(1.0));
    scene("0, -3, 0.5", "0, 0, 0", "", &body)
}

/// The camera looks down through the slab at a constant sky of radiance 1 behind it:
/// exp(-sigma_t d) per channel.
#[test]
fn absorbing_slab_against_the_sky() {
    let xml = slab_against_the_sky();
    check("slab, sky", &xml, 40_000, beer(1.0, THICKNESS));
    // Control: the same render against 5% more extinction.
    control(
        "slab, sky, sigma_t 5% high",
        &xml,
        40_000,
        beer(1.05, THICKNESS),
    );
}

/// A diffuse floor (albedo 0.5) at z = 0 lit straight down by a directional light of irradiance
/// 2 through the slab, seen from below the slab: (0.5 / pi) 2 exp(-sigma_t d). The light is a
/// delta, so only the shadow ray's transmittance through the two null surfaces carries it.
#[test]
fn absorbing_slab_on_a_shadow_ray() {
    let xml = slab_on_a_shadow_ray();
    let expected = beer(1.0, THICKNESS).map(|t| t / std::f64::consts::PI);
    check("slab, shadow ray", &xml, 20_000, expected);
    let wrong = beer(1.05, THICKNESS).map(|t| t / std::f64::consts::PI);
    control("slab, shadow ray, sigma_t 5% high", &xml, 20_000, wrong);
}

/// A sphere of radius 1 filled with a medium of albedo 1 (`sigma_t` and `phase` as given) under
/// a sky of radiance 1; the camera outside (`inside` false) or inside it.
pub(crate) fn furnace(sigma_t: &str, phase: &str, inside: bool) -> String {
    let body = format!(
        r#"<medium type="homogeneous" id="m">
    {sigma_t}
    <float name="albedo" value="1"/>
    {phase}
  </medium>
  <shape type="sphere">
    <float name="radius" value="1"/>
    <bsdf type="null"/>
    <ref name="interior" id="m"/>
  </shape>
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter>"#
    );
    if inside {
        scene("0.2, 0.1, 0.3", "0, 0, -1", "m", &body)
    } else {
        scene("0, 0, 4", "0, 0, 0", "", &body)
    }
}

fn furnace_case(label: &str, xml: &str) {
    check(label, xml, 200_000, [1.0; 3]);
    control(&format!("{label} against 0.99"), xml, 200_000, [0.99; 3]);
}

#[test]
fn white_furnace_isotropic() {
    let xml = furnace(r#"<float name="sigma_t" value="2"/>"#, "", false);
    furnace_case("furnace, g = 0", &xml);
}

#[test]
fn white_furnace_hg() {
    let xml = furnace(
        r#"<float name="sigma_t" value="2"/>"#,
        r#"<phase type="hg"><float name="g" value="0.7"/></phase>"#,
        false,
    );
    furnace_case("furnace, hg g = 0.7", &xml);
}

/// Extinction that differs per channel exercises the channel-mixture weights.
#[test]
fn white_furnace_chromatic_extinction() {
    let xml = furnace(
        r#"<rgb name="sigma_t" value="0.25, 0.5, 1.0"/><float name="scale" value="3"/>"#,
        r#"<phase type="hg"><float name="g" value="0.7"/></phase>"#,
        false,
    );
    furnace_case("furnace, chromatic sigma_t, hg g = 0.7", &xml);
}

/// The camera inside the medium (a medium on the sensor) sees 1 as well.
/// SGGX sheet-like flakes (one voxel): extinction that depends on the direction.
#[test]
fn white_furnace_sggx() {
    let s = tessera_tests::scenes_dir().join("media/flakes_uniform.vol");
    let phase = format!(
        r#"<phase type="sggx"><volume type="gridvolume" name="S">
      <string name="filename" value="{}"/></volume></phase>"#,
        s.display()
    );
    let xml = furnace(r#"<float name="sigma_t" value="2"/>"#, &phase, false);
    furnace_case("furnace, sggx", &xml);
}

#[test]
fn white_furnace_camera_inside() {
    let xml = furnace(r#"<float name="sigma_t" value="2"/>"#, "", true);
    furnace_case("furnace, camera inside", &xml);
}

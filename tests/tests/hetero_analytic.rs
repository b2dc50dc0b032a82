//! `volpath` through heterogeneous media against closed forms, by Student's t-test on the
//! samples of one pixel (1x1 image, field of view 0.001 degrees), as `media_analytic.rs` does for
//! homogeneous media:
//! - an absorbing slab whose extinction is a voxel grid varying along the ray (4 voxels deep,
//!   3 channels: the optical depth of the clamped trilinear profile is a trapezoid sum), seen
//!   directly against a constant sky (delta tracking on the camera ray) and crossed by a shadow
//!   ray toward a directional light (ratio tracking): `exp(-tau)` per channel;
//! - white furnaces: a grid medium of albedo 1 inside a `null` sphere under a sky of radiance 1,
//!   every pixel 1: isotropic, Henyey-Greenstein g = 0.7, a 3-channel (chromatic) grid, and
//!   SGGX microflakes whose matrix varies over a 6-channel grid (`scenes/media/flakes.vol`), so
//!   that the extinction depends on place and direction: light is still conserved.
//!
//! Significance 0.01, Sidak-corrected over the file; each case has a control (the slab against
//! 5% more extinction, the furnaces against 0.99) that must be rejected.
use tessera_tests::pixel_ttest::{check_pixel, control_pixel as control};

/// t-tests in this file: 2 slabs + 4 furnaces, 3 channels each.
const N_TESTS: usize = 6 * 3;

/// The slab's voxels along z (bottom to top), per channel.
const SLAB: [[f64; 4]; 3] = [
    [0.1, 0.3, 0.2, 0.6],
    [0.5, 0.2, 0.9, 0.4],
    [1.2, 0.8, 0.3, 0.1],
];
const THICKNESS: f64 = 1.5;

/// Writes a `.vol` file of `res` voxels, `channels` each (x fastest), into the temp folder.
fn write_vol(
    name: &str,
    res: [usize; 3],
    channels: usize,
    value: impl Fn(usize, usize, usize, usize) -> f32,
) -> String {
    let mut b = b"VOL\x03".to_vec();
    for v in [1, res[0], res[1], res[2], channels] {
        b.extend_from_slice(&(v as i32).to_le_bytes());
    }
    for v in [0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for z in 0..res[2] {
        for y in 0..res[1] {
            for x in 0..res[0] {
                for c in 0..channels {
                    b.extend_from_slice(&value(x, y, z, c).to_le_bytes());
                }
            }
        }
    }
    let dir = std::env::temp_dir().join(format!("tessera-hetero-analytic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let p = dir.join(name);
    std::fs::write(&p, b).expect("write .vol");
    p.display().to_string()
}

/// The slab's optical depth per channel along z, times `scale`: cell-centred trilinear values
/// clamped at the ends integrate to the trapezoid sum plus half a voxel of each end value.
fn slab_tau(scale: f64) -> [f64; 3] {
    SLAB.map(|v| {
        let n = v.len();
        let inner: f64 = (0..n - 1).map(|i| (v[i] + v[i + 1]) / 2.0).sum();
        scale * THICKNESS / n as f64 * (inner + v[0] / 2.0 + v[n - 1] / 2.0)
    })
}

/// A 1x1 camera at `origin` looking at `target`.
fn scene(origin: &str, target: &str, body: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="volpath"/>
  <sensor type="perspective">
    <float name="fov" value="0.001"/>
    <transform name="to_world"><lookat origin="{origin}" target="{target}" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
  </sensor>
{body}
</scene>"#
    )
}

/// The slab between z = 1 and z = 1 + THICKNESS, 40 wide, absorbing only, bounded by `null`.
fn slab() -> String {
    let vol = write_vol("slab.vol", [1, 1, 4], 3, |_, _, z, c| SLAB[c][z] as f32);
    let half = THICKNESS / 2.0;
    format!(
        r#"<shape type="cube">
    <transform name="to_world"><scale x="20" y="20" z="{half}"/><translate z="{z}"/></transform>
    <bsdf type="null"/>
    <medium type="heterogeneous" name="interior">
      <volume type="gridvolume" name="sigma_t">
        <string name="filename" value="{vol}"/>
        <transform name="to_world"><scale x="40" y="40" z="{THICKNESS}"/><translate x="-20" y="-20" z="1"/></transform>
      </volume>
      <float name="albedo" value="0"/>
    </medium>
  </shape>"#,
        z = 1.0 + half
    )
}

fn check(label: &str, xml: &str, spp: u64, expected: [f64; 3]) {
    check_pixel(label, xml, spp, expected, N_TESTS);
}

fn beer(scale: f64) -> [f64; 3] {
    slab_tau(scale).map(|t| (-t).exp())
}

/// The camera looks down through the slab at a sky of radiance 1: exp(-tau) per channel.
#[test]
fn grid_slab_against_the_sky() {
    let body = format!(
        "{}\n  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"1\"/></emitter>",
        slab()
    );
    let xml = scene("0, 0, 5", "0, 0, 0", &body);
    check("grid slab, sky", &xml, 40_000, beer(1.0));
    control("grid slab, sky, sigma_t 5% high", &xml, 40_000, beer(1.05));
}

/// A diffuse floor (albedo 0.5) lit straight down by a directional light of irradiance 2 through
/// the slab, seen from below it: (0.5 / pi) 2 exp(-tau); only the shadow ray carries the light.
#[test]
fn grid_slab_on_a_shadow_ray() {
    let body = format!("{}{}", slab(), crate::media_analytic::LIT_FLOOR);
    let xml = scene("0, -3, 0.5", "0, 0, 0", &body);
    let pi = std::f64::consts::PI;
    check(
        "grid slab, shadow ray",
        &xml,
        20_000,
        beer(1.0).map(|t| t / pi),
    );
    let wrong = beer(1.05).map(|t| t / pi);
    control(
        "grid slab, shadow ray, sigma_t 5% high",
        &xml,
        20_000,
        wrong,
    );
}

/// The box [-0.55, 0.55]^3 of the furnaces' grids.
const FURNACE_BOX: &str = r#"<transform name="to_world"><scale value="1.1"/><translate x="-0.55" y="-0.55" z="-0.55"/></transform>"#;

/// A grid medium of albedo 1 in the box [-0.55, 0.55]^3 inside a null sphere of radius 1, under
/// a sky of radiance 1, seen from outside.
fn furnace(channels: usize, phase: &str) -> String {
    let name = format!("furnace{channels}.vol");
    let vol = write_vol(&name, [5, 4, 6], channels, |x, y, z, c| {
        (((x * 7 + y * 3 + z * 5 + c * 4) % 11) as f32) * 0.4
    });
    let body = format!(
        r#"<medium type="heterogeneous" id="m">
    <volume type="gridvolume" name="sigma_t">
      <string name="filename" value="{vol}"/>
      {FURNACE_BOX}
    </volume>
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
    scene("0.1, 0.05, 4", "0, 0, 0", &body)
}

fn furnace_case(label: &str, xml: &str) {
    check(label, xml, 100_000, [1.0; 3]);
    control(&format!("{label} against 0.99"), xml, 100_000, [0.99; 3]);
}

#[test]
fn grid_white_furnace_isotropic() {
    furnace_case("grid furnace, g = 0", &furnace(1, ""));
}

#[test]
fn grid_white_furnace_hg() {
    let phase = r#"<phase type="hg"><float name="g" value="0.7"/></phase>"#;
    furnace_case("grid furnace, hg g = 0.7", &furnace(1, phase));
}

/// SGGX flakes whose matrix varies through the box: extinction `sigma_t sqrt(w^T S w)` that
/// depends on the direction, majorants bounded over every direction.
#[test]
fn grid_white_furnace_sggx() {
    let s = tessera_tests::scenes_dir().join("media/flakes.vol");
    let phase = format!(
        r#"<phase type="sggx"><volume type="gridvolume" name="S">
      <string name="filename" value="{}"/>{FURNACE_BOX}</volume></phase>"#,
        s.display()
    );
    furnace_case(
        "grid furnace, sggx from a 6-channel grid",
        &furnace(1, &phase),
    );
}

/// Extinction that differs per channel and per voxel exercises the channel ratios' null events.
#[test]
fn grid_white_furnace_chromatic() {
    let phase = r#"<phase type="hg"><float name="g" value="0.7"/></phase>"#;
    furnace_case(
        "grid furnace, 3-channel sigma_t, hg g = 0.7",
        &furnace(3, phase),
    );
}

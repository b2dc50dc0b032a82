//! The `projector` and the textured `spot` against closed forms, through the emitters' own
//! sampling (`Emitter::sample` at chosen points), loaded from scene text.
//!
//! - Per texel: a plane facing a projector at depth `d` receives irradiance `pi scale E / d^2`
//!   under each texel `E` of its image (nearest lookups), wherever the texel lies in the
//!   frustum; checked at every texel's centre, which also fixes where each texel lands (first
//!   column toward local +x, first row toward +y) and the frustum's aspect ratio (the image's).
//!   Control: the image mirrored in `u` fails.
//! - Flux: a tilted plane across the whole frustum receives the projector's power,
//!   `pi scale mean(E) 4 tan_x tan_y`; a Monte Carlo integral over the plane, t-tested per
//!   channel. Control: the closed form for a field of view 5% wider is rejected.
//! - Textured spot flux: a plane across the cone receives `I mean(T) Omega`, with `Omega` the
//!   falloff's solid angle, for a checkerboard, whose four squares split the cone into four
//!   equal quadrants. Control: the texture left out of the closed form is rejected.
//!
//! Significance 0.01, Sidak-corrected over the t-tests of this file (2 fluxes x 3 channels).
use std::f64::consts::PI;
use std::path::PathBuf;

use glam::{Vec2, Vec3};
use tessera::image_io::{write_image, RgbImage};
use tessera_core::emitter::Emitter;
use tessera_core::geometry::Interaction;
use tessera_core::math::{Frame, Norm};
use tessera_lab::stats::{sidak_alpha, t_test_mean, Moments, Pcg32};
use tessera_tests::load_xml;

const N_TESTS: usize = 2 * 3;

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// A 4x2 image with a distinct value per texel and channel, written as a linear EXR in a
/// directory of its own (`name`: one per test, as tests run in parallel).
fn image(name: &str) -> (PathBuf, RgbImage) {
    let dir = std::env::temp_dir().join(format!("tessera-projector-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("texels.exr");
    let img = RgbImage {
        width: 4,
        height: 2,
        data: (0..8)
            .map(|i| {
                let (x, y) = ((i % 4) as f32, (i / 4) as f32);
                [1.0 + x, 1.0 + 2.0 * y, 0.5 + x + 3.0 * y]
            })
            .collect(),
    };
    write_image(&path, &img).expect("write the image");
    (path, img)
}

/// The first emitter of a scene holding only `emitter`.
fn emitter(emitter: &str) -> Emitter {
    let l = load_xml(
        &format!(r#"<scene version="3.0.0"><sensor type="perspective"/>{emitter}</scene>"#),
        &[],
    );
    l.scene.emitters[0].clone()
}

/// A projector of `image` (nearest lookups), `scale` 1.5, horizontal field of view `fov`,
/// `mirror` flipping the image in u, placed by `to_world`.
fn projector(image: &std::path::Path, fov: f64, mirror: bool, to_world: &str) -> Emitter {
    let to_uv = if mirror {
        r#"<transform name="to_uv"><scale x="-1" y="1"/></transform>"#
    } else {
        ""
    };
    emitter(&format!(
        r#"<emitter type="projector">
  <float name="fov" value="{fov}"/>
  <float name="scale" value="1.5"/>
  <texture type="bitmap" name="irradiance">
    <string name="filename" value="{}"/>
    <string name="filter_type" value="nearest"/>{to_uv}
  </texture>
  <transform name="to_world">{to_world}</transform>
</emitter>"#,
        image.display()
    ))
}

/// A point at `p` of a surface with normal `n`.
fn at(p: Vec3, n: Vec3) -> Interaction {
    Interaction {
        p,
        p_err: Vec3::ZERO,
        t: 1.0,
        ng: n,
        frame: Frame::from_normal(n),
        uv: Vec2::ZERO,
        shape: 0,
        wi: n,
    }
}

/// Irradiance at `p` on a surface of normal `n` (zero where the light does not reach).
fn irradiance(e: &Emitter, p: Vec3, n: Vec3) -> Vec3 {
    let ctx_shapes = [];
    let ctx = tessera_core::emitter::EmitterCtx {
        shapes: &ctx_shapes,
        disks: &[],
        scene_center: Vec3::ZERO,
        scene_radius: 10.0,
    };
    match e.sample(&ctx, &at(p, n), Vec2::splat(0.5)) {
        Some(s) => {
            assert!(s.delta && s.pdf == 1.0 && s.target.is_some());
            s.weight * s.wo.dot(n).abs()
        }
        None => Vec3::ZERO,
    }
}

/// Worst relative error, over the texel centres of a plane facing the projector at depth 2,
/// against `pi 1.5 E / 4` of the texel there.
fn worst_texel_error(mirror: bool) -> f64 {
    let (path, img) = image(if mirror { "mirrored" } else { "texels" });
    let fov = 50.0_f64;
    // Rotated 90 degrees about z, then moved: local +x is world +y, local +y is world -x,
    // local +z is world +z.
    let e = projector(
        &path,
        fov,
        mirror,
        r#"<rotate z="1" angle="90"/><translate x="0.5" y="-0.25" z="1"/>"#,
    );
    let origin = Vec3::new(0.5, -0.25, 1.0);
    let depth = 2.0_f64;
    let tan_x = (fov.to_radians() / 2.0).tan();
    let tan_y = tan_x * img.height as f64 / img.width as f64;
    let mut worst = 0.0_f64;
    for j in 0..img.height {
        for i in 0..img.width {
            let u = (i as f64 + 0.5) / img.width as f64;
            let v = (j as f64 + 0.5) / img.height as f64;
            // u = 1/2 - x / (2 z tan_x): the first column toward local +x.
            let x = (0.5 - u) * 2.0 * depth * tan_x;
            let y = (0.5 - v) * 2.0 * depth * tan_y;
            let local_to_world = |x: f64, y: f64, z: f64| Vec3::new(-y as f32, x as f32, z as f32);
            let p = origin + local_to_world(x, y, depth);
            let got = irradiance(&e, p, Vec3::NEG_Z);
            let texel = img.data[(j * img.width + i) as usize];
            for k in 0..3 {
                let want = PI * 1.5 * texel[k] as f64 / (depth * depth);
                worst = worst.max((got[k] as f64 - want).abs() / want);
            }
        }
    }
    let _ = std::fs::remove_dir_all(path.parent().expect("dir"));
    worst
}

#[test]
fn each_texel_lights_its_place_on_a_facing_plane() {
    let worst = worst_texel_error(false);
    println!("projector texels: worst relative error {worst:.2e}");
    assert!(worst < 1e-4, "worst relative error {worst:.2e}");
    let mirrored = worst_texel_error(true);
    println!("mirrored image: worst relative error {mirrored:.2e}");
    assert!(
        mirrored > 0.1,
        "a mirrored image went unnoticed ({mirrored:.2e})"
    );
}

/// Monte Carlo flux through the plane `z = z0 + slope x` (light-local coordinates, light at
/// the origin looking along +z) over `|x|, |y| <= half`, per channel.
fn flux(e: &Emitter, z0: f32, slope: f32, half: f32, n: usize, seed: u64) -> [Moments; 3] {
    let mut rng = Pcg32::new(seed);
    let normal = Vec3::new(slope, 0.0, -1.0).unit();
    // Area of the region on the tilted plane per unit of projected (x, y) area.
    let stretch = (1.0 + slope * slope).sqrt() as f64;
    let area = (2.0 * half as f64).powi(2) * stretch;
    let mut m = [Moments::new(), Moments::new(), Moments::new()];
    for _ in 0..n {
        let s = rng.next_vec2();
        let x = (2.0 * s.x - 1.0) * half;
        let y = (2.0 * s.y - 1.0) * half;
        let p = Vec3::new(x, y, z0 + slope * x);
        let e_irr = irradiance(e, p, normal);
        for k in 0..3 {
            m[k].push(area * e_irr[k] as f64);
        }
    }
    m
}

#[test]
fn a_plane_across_the_frustum_receives_the_projectors_power() {
    let (path, img) = image("flux");
    let fov = 40.0_f64;
    let e = projector(&path, fov, false, "");
    let m = flux(&e, 2.0, 0.5, 2.0, 400_000, 3);
    let power = |fov: f64| {
        let tan_x = (fov.to_radians() / 2.0).tan();
        let tan_y = tan_x * img.height as f64 / img.width as f64;
        let n = img.data.len() as f64;
        let mut p = [0.0; 3];
        for k in 0..3 {
            let mean = img.data.iter().map(|t| t[k] as f64).sum::<f64>() / n;
            p[k] = PI * 1.5 * mean * 4.0 * tan_x * tan_y;
        }
        p
    };
    let want = power(fov);
    let wide = power(fov * 1.05);
    let mut control_rejected = false;
    for k in 0..3 {
        let r = t_test_mean(&m[k], want[k]);
        println!(
            "projector flux ch{k}: {:.5} vs {:.5}: {r}",
            m[k].mean(),
            want[k]
        );
        assert!(r.passes(alpha()), "channel {k}: {r}");
        let c = t_test_mean(&m[k], wide[k]);
        println!("  control, fov 5% wider: {:.5}: {c}", wide[k]);
        control_rejected |= !c.passes(alpha());
    }
    assert!(control_rejected, "a field of view 5% off went unnoticed");
    let _ = std::fs::remove_dir_all(path.parent().expect("dir"));
}

#[test]
fn a_textured_spot_emits_its_intensity_times_the_mean_over_its_cone() {
    let intensity = [3.0, 2.0, 1.0];
    let e = emitter(
        r#"<emitter type="spot">
  <rgb name="intensity" value="3, 2, 1"/>
  <float name="cutoff_angle" value="30"/>
  <float name="beam_width" value="15"/>
  <texture type="checkerboard" name="texture">
    <rgb name="color0" value="0.9, 0.1, 0.5"/>
    <rgb name="color1" value="0.1, 0.3, 0.5"/>
  </texture>
</emitter>"#,
    );
    // The cone meets z = 1 within radius tan 30 = 0.58; the plane z = 1 + 0.3 x across it.
    let m = flux(&e, 1.0, 0.3, 1.5, 400_000, 5);
    let (c, b) = (30.0_f64.to_radians(), 15.0_f64.to_radians());
    let omega = 2.0 * PI * (1.0 - (c.sin() - b.sin()) / (c - b));
    let mean = [0.5, 0.2, 0.5];
    let mut control_rejected = false;
    for k in 0..3 {
        let want = intensity[k] * mean[k] * omega;
        let r = t_test_mean(&m[k], want);
        println!("spot flux ch{k}: {:.5} vs {want:.5}: {r}", m[k].mean());
        assert!(r.passes(alpha()), "channel {k}: {r}");
        let without = intensity[k] * omega;
        control_rejected |= !t_test_mean(&m[k], without).passes(alpha());
    }
    assert!(control_rejected, "the texture left out went unnoticed");
}

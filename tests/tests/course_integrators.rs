//! The course integrators (Nori's `normals`, `simple`, `ao`, `whitted`; the Wakame assignment's
//! `av`) against closed forms, each with a control that must fail.
//!
//! Each case renders a 1x1 image through a 0.001 degree field of view (box filter) looking
//! straight down at the origin of a diffuse square in the plane z = 0. Random estimators are
//! t-tested per channel at significance 0.01, Sidak-corrected over the file; deterministic ones
//! (every sample the same up to rounding) are compared with a relative tolerance of 1e-4.
use std::f64::consts::PI;
use tessera_core::film::PixelAccum;
use tessera_lab::stats::{sidak_alpha, t_test_from_sums};
use tessera_tests::analytic_scenes::one_pixel_over_square;
use tessera_tests::{load_xml, render_loaded};

/// t-tests in this file: ao, av (two lengths), whitted (mirror, diffuse), 3 channels each.
const N_TESTS: usize = 5 * 3;

/// A 1x1 view from (0, 0, `eye`) straight down, `integrator` and `body` added.
fn scene(eye: f64, integrator: &str, body: &str) -> String {
    let lookat = format!(r#"origin="0, 0, {eye}" target="0, 0, 0" up="0, 1, 0""#);
    one_pixel_over_square(integrator, &lookat, body)
}

/// An occluding disk of radius `r` at height `h` above the origin, facing down.
fn disk(r: f64, h: f64) -> String {
    format!(
        r#"<shape type="disk"><transform name="to_world"><scale value="{r}"/><rotate x="1" angle="180"/><translate z="{h}"/></transform></shape>"#
    )
}

fn render(xml: &str, spp: u64) -> PixelAccum {
    let l = load_xml(xml, &[]);
    *render_loaded(&l, spp, 11).at(0, 0)
}

/// Whether every channel's mean passes a t-test against `expected` at the file's level.
fn passes(p: &PixelAccum, expected: [f64; 3]) -> bool {
    let alpha = sidak_alpha(0.01, N_TESTS);
    assert_eq!(p.dropped, 0);
    (0..3).all(|k| {
        t_test_from_sums(p.count as f64, p.sum[k], p.sum_sq[k], expected[k]).p_value >= alpha
    })
}

fn mean(p: &PixelAccum) -> [f64; 3] {
    [0, 1, 2].map(|k| p.sum[k] / p.count as f64)
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter()
        .zip(&b)
        .all(|(a, b)| (a - b).abs() <= 1e-4 * b.abs().max(1e-6))
}

#[test]
fn normals_shows_the_absolute_shading_normal() {
    // The square turned 40 degrees about x: its normal is (0, -sin 40, cos 40), seen as its
    // absolute value.
    let tilted = r#"<shape type="rectangle"><transform name="to_world"><scale value="10"/><rotate x="1" angle="40"/><translate z="0.5"/></transform></shape>"#;
    let p = render(&scene(3.0, r#"<integrator type="normals"/>"#, tilted), 4);
    let a = 40f64.to_radians();
    assert!(close(mean(&p), [0.0, a.sin(), a.cos()]), "{:?}", mean(&p));
    // Control: the untilted normal.
    assert!(!close(mean(&p), [0.0, 0.0, 1.0]));
    // Nothing hit: black.
    let up = scene(3.0, r#"<integrator type="normals"/>"#, "")
        .replace("target=\"0, 0, 0\"", "target=\"0, 0, 9\"");
    assert_eq!(mean(&render(&up, 2)), [0.0; 3]);
}

#[test]
fn simple_is_energy_over_four_pi_squared_cos_over_distance_squared() {
    let (h, energy) = (2.0, [100.0, 50.0, 10.0]);
    let integrator = format!(
        r#"<integrator type="simple"><point name="position" value="0.6, 0, {h}"/><rgb name="energy" value="{}, {}, {}"/></integrator>"#,
        energy[0], energy[1], energy[2]
    );
    let p = render(&scene(5.0, &integrator, ""), 4);
    let d2: f64 = 0.36 + h * h;
    let cos = h / d2.sqrt();
    let want = energy.map(|e| e / (4.0 * PI * PI) * cos / d2);
    assert!(close(mean(&p), want), "{:?} vs {want:?}", mean(&p));
    // Control: the 1/(4 pi) of a point light's radiant intensity instead of Nori's 1/(4 pi^2).
    assert!(!close(mean(&p), want.map(|v| v * PI)));
    // In the shadow of a disk between the light and the floor: black.
    let shadowed = render(
        &scene(
            5.0,
            &integrator,
            &disk(0.1, 1.0).replace("<translate z=\"1\"/>", "<translate x=\"0.3\" z=\"1\"/>"),
        ),
        4,
    );
    assert_eq!(mean(&shadowed), [0.0; 3]);
    // Without its light the integrator is refused, with the location.
    let text = scene(
        5.0,
        r#"<integrator type="simple"><rgb name="energy" value="1"/></integrator>"#,
        "",
    );
    let e = tessera_scene::load_scene_str(&text, std::path::Path::new("/nowhere/s.xml"), &[])
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("/nowhere/s.xml:2:") && e.contains("position"),
        "{e}"
    );
}

#[test]
fn ao_and_av_under_an_occluding_disk() {
    // Seen from the origin, a disk of radius r at height h covers the cone of half-angle
    // atan(r / h): cosine-weighted, the open part is cos^2 of that angle; uniformly weighted,
    // its cosine (while the segments reach the disk).
    let (r, h) = (1.5f64, 2.0f64);
    let cos_max = h / (r * r + h * h).sqrt();
    let spp = 20_000;
    let ao = render(&scene(1.0, r#"<integrator type="ao"/>"#, &disk(r, h)), spp);
    assert!(passes(&ao, [cos_max * cos_max; 3]), "ao {:?}", mean(&ao));
    assert!(
        !passes(&ao, [cos_max; 3]),
        "control: uniform weighting must fail for ao"
    );
    let av_long = r#"<integrator type="av"><float name="length" value="10"/></integrator>"#;
    let av = render(&scene(1.0, av_long, &disk(r, h)), spp);
    assert!(passes(&av, [cos_max; 3]), "av {:?}", mean(&av));
    assert!(
        !passes(&av, [cos_max * cos_max; 3]),
        "control: cosine weighting must fail for av"
    );
    // Segments shorter than the way to the disk see nothing: every sample is 1.
    let av_short = r#"<integrator type="av"><float name="length" value="1.9"/></integrator>"#;
    let short = render(&scene(1.0, av_short, &disk(r, h)), 1000);
    assert_eq!(mean(&short), [1.0; 3]);
    // Nothing hit: ao black, av white.
    let sky = |i: &str| {
        render(
            &scene(1.0, i, "").replace("target=\"0, 0, 0\"", "target=\"0, 0, 9\""),
            2,
        )
    };
    assert_eq!(mean(&sky(r#"<integrator type="ao"/>"#)), [0.0; 3]);
    assert_eq!(mean(&sky(av_long)), [1.0; 3]);
}

#[test]
fn whitted_follows_mirrors_without_bias_and_lights_diffuse_surfaces_directly() {
    // A mirror square seen from above reflects a large emitting square facing down: each
    // sample is 0 or Le / 0.95, with mean Le.
    let mirror = r#"<shape type="rectangle"><transform name="to_world"><scale value="10"/><translate z="0.5"/></transform><bsdf type="mirror"/></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="10"/><rotate x="1" angle="180"/><translate z="3"/></transform><emitter type="area"><rgb name="radiance" value="2, 1, 0.5"/></emitter></shape>"#;
    let p = render(
        &scene(1.0, r#"<integrator type="whitted"/>"#, mirror),
        20_000,
    );
    assert!(passes(&p, [2.0, 1.0, 0.5]), "mirror {:?}", mean(&p));
    assert!(
        !passes(&p, [1.9, 0.95, 0.475]),
        "control: without the 1/0.95 it must fail"
    );
    // A diffuse floor under a constant sky of radiance L reflects albedo * L.
    let sky = r#"<emitter type="constant"><rgb name="radiance" value="1.5"/></emitter>"#;
    let p = render(&scene(1.0, r#"<integrator type="whitted"/>"#, sky), 200_000);
    let want = [0.7 * 1.5, 0.5 * 1.5, 0.3 * 1.5];
    assert!(passes(&p, want), "diffuse {:?}", mean(&p));
    assert!(
        !passes(&p, want.map(|v| v * 1.02)),
        "control: 2% off must fail"
    );
}

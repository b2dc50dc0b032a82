//! Mitsuba 3's cameras against closed forms: the thin lens's aperture sampling (chi-square), its
//! focus (a sharp edge on the plane in focus renders as the pinhole renders it) and its blur
//! (an edge off that plane spreads by the circle of confusion the thin-lens formula predicts),
//! the orthographic projection (parallel rays, a sphere's silhouette of the size `to_world`
//! gives) and the principal point offsets (the image moves by the predicted number of pixels).
//! Every statistical test has a control that must fail.
//!
//! The rendered scenes see a large emitting rectangle of radiance 1 directly, with a box
//! filter: a pixel's expected value is the fraction of its footprint (and of the lens) whose
//! rays reach the emitter. Edges lie on pixel boundaries, so a pinhole image is exactly 0 or 1
//! in every pixel.
use glam::{Vec2, Vec3};
use std::f64::consts::PI;
use tessera::render::Framebuffer;
use tessera_core::camera::{Camera, FovAxis, Perspective, Projection, ThinLens};
use tessera_core::math::Transform;
use tessera_core::sampling::{IndependentSampler, Sampler};
use tessera_lab::stats::{chi2_test, sidak_alpha, Chi2Result, PlaneChi2, DEFAULT_MIN_EXPECTED};
use tessera_tests::{load_xml, render_loaded, t_test_f32};

/// Statistical tests in this file (each at the Šidák-corrected level): aperture chi-square
/// (through `generate_ray_through`, through the render path's sampler), blur in front of and
/// behind the plane in focus with each sampler, orthographic silhouette.
const N_TESTS: usize = 7;

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// Image size (square) of the rendered tests.
const RES: u32 = 64;
/// Horizontal field of view of the rendered tests, in degrees.
const FOV: f64 = 45.0;

/// A scene seeing, from the origin along +z, a 100 x 100 emitting rectangle at depth `depth`
/// that covers world x > 0 (`vertical`) or y > 0; `sensor` is the sensor's type and extra
/// elements; the `independent` sampler.
fn edge_scene(sensor: &str, extra: &str, depth: f64, vertical: bool, spp: u32) -> String {
    edge_scene_sampled(sensor, extra, depth, vertical, spp, "independent")
}

/// [`edge_scene`] with the sampler `sampler`.
fn edge_scene_sampled(
    sensor: &str,
    extra: &str,
    depth: f64,
    vertical: bool,
    spp: u32,
    sampler: &str,
) -> String {
    let (cx, cy) = if vertical { (50.0, 0.0) } else { (0.0, 50.0) };
    format!(
        r#"<scene version="3.0.0">
  <integrator type="direct"/>
  <sensor type="{sensor}">
    {extra}
    <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, 1" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="{RES}"/><integer name="height" value="{RES}"/><rfilter type="box"/></film>
    <sampler type="{sampler}"><integer name="sample_count" value="{spp}"/></sampler>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world">
      <rotate y="1" angle="180"/><scale value="50"/><translate x="{cx}" y="{cy}" z="{depth}"/>
    </transform>
    <emitter type="area"><rgb name="radiance" value="1, 1, 1"/></emitter>
  </shape>
</scene>"#
    )
}

/// Renders `xml` with `spp` samples.
fn render(xml: &str, spp: u64, seed: u64) -> Framebuffer {
    render_loaded(&load_xml(xml, &[]), spp, seed)
}

/// The red channel's mean at pixel `(x, y)`.
fn value(fb: &Framebuffer, x: u32, y: u32) -> f64 {
    let p = fb.at(x, y);
    p.sum[0] / p.count as f64
}

/// Pixel `k` of line `line` across an edge: of row `line` for a vertical edge, of column
/// `line` for a horizontal one.
fn at(fb: &Framebuffer, line: u32, k: u32, vertical: bool) -> f64 {
    if vertical {
        value(fb, k, line)
    } else {
        value(fb, line, k)
    }
}

/// Per line across an edge (rows for a vertical edge), how far the image departs from the
/// sharp `step`: `sum_k |v_k - step_k|` with the sign taken from the step (unbiased under
/// noise). For an edge blurred by the x-coordinate of a uniform disk of radius `R` pixels, its
/// expectation is `R * E|x| = 4 R / (3 pi)`, whatever the box filter's footprint (the edge lies
/// on a pixel boundary).
fn edge_widths(fb: &Framebuffer, step: &[f64], vertical: bool) -> Vec<f64> {
    (0..RES)
        .map(|line| {
            (0..RES)
                .map(|k| {
                    let s = step[k as usize];
                    (at(fb, line, k, vertical) - s) * (1.0 - 2.0 * s)
                })
                .sum()
        })
        .collect()
}

/// The sharp step of a pinhole image across its lines: each pixel rounded to 0 or 1 (it is
/// exactly one of them up to float rounding at the edge), required equal on every line.
fn step_of(fb: &Framebuffer, vertical: bool) -> Vec<f64> {
    let step: Vec<f64> = (0..RES).map(|k| at(fb, 0, k, vertical).round()).collect();
    for line in 0..RES {
        for k in 0..RES {
            let v = at(fb, line, k, vertical);
            assert!(
                (v - step[k as usize]).abs() < 1e-3,
                "pinhole pixel {k} of line {line}: {v}"
            );
        }
    }
    step
}

/// Two-sided p-value of the mean of `xs` against `expected`.
fn p_value(xs: &[f64], expected: f64) -> f64 {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    t_test_f32(n, mean, var, expected).1
}

fn mean(xs: &[f64]) -> f64 {
    xs.iter().sum::<f64>() / xs.len() as f64
}

/// Pixels per unit of the image plane at depth 1 (horizontal field of view [`FOV`]).
fn pixels_per_unit() -> f64 {
    RES as f64 / (2.0 * (0.5 * FOV).to_radians().tan())
}

/// A thin lens of radius `r` focused at `focus`, at the origin looking along +z.
fn lens_camera(r: f32, focus: f32) -> Camera {
    let pinhole = Perspective::new(RES, RES, FOV as f32, FovAxis::X, 0.01, 1e4);
    Camera {
        to_world: Transform::IDENTITY,
        width: RES,
        height: RES,
        projection: Projection::ThinLens(ThinLens {
            pinhole,
            aperture_radius: r,
            focus_distance: focus,
        }),
        crop: None,
    }
}

/// The point where `ray` (from the camera at the origin) crosses the lens plane z = 0.
fn aperture_point(ray: &tessera_core::math::Ray) -> Vec3 {
    ray.o - ray.d * (ray.o.z / ray.d.z)
}

/// Density on `[0,1]^2` of a uniform point of the unit disk mapped by `p = (q + 1) / 2`.
fn disk_density(p: Vec2) -> f64 {
    let q = 2.0 * p - Vec2::ONE;
    if q.length_squared() <= 1.0 {
        4.0 / PI
    } else {
        0.0
    }
}

/// A control density: the polar map without the square root (radius = u), `1 / (2 pi rho)` on
/// the unit disk, mapped the same way.
fn polar_density(p: Vec2) -> f64 {
    let q = 2.0 * p - Vec2::ONE;
    let rho = (q.x as f64).hypot(q.y as f64);
    if rho <= 1.0 {
        4.0 / (2.0 * PI * rho.max(1e-9))
    } else {
        0.0
    }
}

fn check(name: &str, r: &Chi2Result, must_pass: bool) {
    println!("{name}: {r}");
    assert_eq!(r.passes(alpha()), must_pass, "{name}: {r}");
}

/// Points on the aperture, recovered from camera rays through random film positions, are
/// uniform on the disk of radius `aperture_radius`; the polar map's density is rejected.
#[test]
fn thin_lens_aperture_is_uniform_on_its_disk() {
    let (r, pos) = (0.25f32, Vec2::new(10.3, 40.7));
    let cam = lens_camera(r, 3.0);
    let to_unit = |u: Vec2| {
        let a = aperture_point(&cam.generate_ray_through(pos, u));
        Some(((Vec2::new(a.x, a.y) / r + Vec2::ONE) * 0.5).clamp(Vec2::ZERO, Vec2::ONE))
    };
    let harness = PlaneChi2 {
        bins_x: 20,
        bins_y: 20,
        samples: 1_000_000,
    };
    check("aperture", &harness.run(to_unit, disk_density, 1), true);
    check(
        "aperture (control: polar density)",
        &harness.run(to_unit, polar_density, 1),
        false,
    );
}

/// The aperture points the render path draws (`Camera::sample_ray` with the pixel's sampler,
/// after the filter's offset) are uniform on the disk too: 20 x 20 cells counted over many
/// samples of one pixel.
#[test]
fn render_path_draws_uniform_aperture_points() {
    let (r, bins, n) = (0.5f32, 20usize, 400_000u64);
    let cam = lens_camera(r, 2.0);
    let mut counts = vec![0.0; bins * bins];
    for index in 0..n {
        let mut s = IndependentSampler::new(7, 5, 9, index);
        let pos = Vec2::new(5.0, 9.0) + s.next_2d();
        let a = aperture_point(&cam.sample_ray(pos, &mut s));
        let p =
            ((Vec2::new(a.x, a.y) / r + Vec2::ONE) * 0.5).clamp(Vec2::ZERO, Vec2::splat(0.999_999));
        counts[(p.y * bins as f32) as usize * bins + (p.x * bins as f32) as usize] += 1.0;
    }
    let expected = |density: fn(Vec2) -> f64| -> Vec<f64> {
        // Each cell's probability by a 32 x 32 midpoint rule, normalized.
        let m = 32;
        let mut e: Vec<f64> = (0..bins * bins)
            .map(|c| {
                let (cx, cy) = ((c % bins) as f64, (c / bins) as f64);
                let mut acc = 0.0;
                for i in 0..m {
                    for j in 0..m {
                        let x = (cx + (i as f64 + 0.5) / m as f64) / bins as f64;
                        let y = (cy + (j as f64 + 0.5) / m as f64) / bins as f64;
                        acc += density(Vec2::new(x as f32, y as f32));
                    }
                }
                acc
            })
            .collect();
        let total: f64 = e.iter().sum();
        e.iter_mut().for_each(|v| *v *= n as f64 / total);
        e
    };
    // Cells the disk's rim cuts get the midpoint rule's error; it is well below the counts'
    // noise at 32 x 32 points a cell.
    let uniform = chi2_test(&counts, &expected(disk_density), DEFAULT_MIN_EXPECTED);
    check("render-path aperture", &uniform, true);
    let polar = chi2_test(&counts, &expected(polar_density), DEFAULT_MIN_EXPECTED);
    check(
        "render-path aperture (control: polar density)",
        &polar,
        false,
    );
}

/// A thin lens focused on the emitter's plane renders its edge as the pinhole does: the same
/// pixels, an edge width of zero. The same lens focused elsewhere does not (control).
#[test]
fn thin_lens_is_sharp_on_the_plane_in_focus() {
    let depth = 3.0;
    let fov = format!(r#"<float name="fov" value="{FOV}"/>"#);
    let pinhole = render(&edge_scene("perspective", &fov, depth, true, 16), 16, 1);
    let step = step_of(&pinhole, true);
    assert_eq!(
        step.iter().sum::<f64>(),
        (RES / 2) as f64,
        "the edge is at the centre"
    );
    let lens = |focus: f64| {
        let extra = format!(
            r#"{fov}<float name="aperture_radius" value="0.5"/><float name="focus_distance" value="{focus}"/>"#
        );
        render(&edge_scene("thinlens", &extra, depth, true, 16), 16, 2)
    };
    let sharp = lens(depth);
    let worst = (0..RES)
        .flat_map(|y| (0..RES).map(move |x| (x, y)))
        .map(|(x, y)| (value(&sharp, x, y) - value(&pinhole, x, y)).abs())
        .fold(0.0, f64::max);
    let width = mean(&edge_widths(&sharp, &step, true));
    println!("in focus: worst pixel difference {worst:.2e}, edge width {width:.2e} px");
    assert!(worst < 0.01 && width.abs() < 0.01);
    let blurred = mean(&edge_widths(&lens(2.0 * depth), &step, true));
    println!("control, focused at twice the depth: edge width {blurred:.3} px");
    assert!(blurred > 1.0, "the control must blur the edge");
}

/// The edge width of a plane at `depth` seen by a lens of radius `r` focused at `focus`, in
/// pixels: its circle of confusion on the image plane has radius `r |1/depth - 1/focus|`
/// (image-plane units at depth 1), and the width is `4 R / (3 pi)` of its radius `R` in pixels.
fn predicted_width(r: f64, depth: f64, focus: f64) -> f64 {
    let coc = r * (1.0 / depth - 1.0 / focus).abs() * pixels_per_unit();
    4.0 * coc / (3.0 * PI)
}

/// Out of focus, the edge is spread by the predicted circle of confusion, in front of the
/// plane in focus (a vertical edge) and behind it (a horizontal one), with either sampler (with
/// `zsobol` the lens's samples come from their own stratified dimensions; pixels are scrambled
/// independently, so rows stay independent estimates). Controls: a circle 10%
/// smaller, and the radius `r |depth - focus| / focus` (the blur measured on the plane in
/// focus instead of the plane of the edge), must be rejected.
#[test]
fn thin_lens_blur_matches_the_circle_of_confusion() {
    let r = 0.5;
    let fov = format!(r#"<float name="fov" value="{FOV}"/>"#);
    for (depth, focus, vertical, seed, sampler) in [
        (2.0, 4.0, true, 3, "independent"),
        (4.0, 2.0, false, 4, "independent"),
        (2.0, 4.0, false, 5, "zsobol"),
        (4.0, 2.0, true, 6, "zsobol"),
    ] {
        let pinhole = render(
            &edge_scene("perspective", &fov, depth, vertical, 4),
            4,
            seed,
        );
        let step = step_of(&pinhole, vertical);
        let extra = format!(
            r#"{fov}<float name="aperture_radius" value="{r}"/><float name="focus_distance" value="{focus}"/>"#
        );
        let xml = edge_scene_sampled("thinlens", &extra, depth, vertical, 64, sampler);
        let fb = render(&xml, 64, seed + 10);
        let widths = edge_widths(&fb, &step, vertical);
        let predicted = predicted_width(r, depth, focus);
        let wrong = 4.0 * r * (depth - focus).abs() / focus * pixels_per_unit() / (3.0 * PI);
        let (p, p_small, p_wrong) = (
            p_value(&widths, predicted),
            p_value(&widths, 0.9 * predicted),
            p_value(&widths, wrong),
        );
        println!(
            "{sampler}, depth {depth}, focus {focus}: width {:.3} px, predicted {predicted:.3} (p = {p:.3}); \
             controls: 0.9x p = {p_small:.2e}, r|z-f|/f ({wrong:.3}) p = {p_wrong:.2e}",
            mean(&widths)
        );
        assert!(
            p >= alpha(),
            "width {} vs {predicted}: p = {p}",
            mean(&widths)
        );
        assert!(p_small < alpha() && p_wrong < alpha(), "a control passed");
    }
}

/// `aperture_radius` 0 is the pinhole: the same image, bit for bit, and no lens sample drawn.
#[test]
fn zero_aperture_is_the_pinhole() {
    let fov = format!(r#"<float name="fov" value="{FOV}"/>"#);
    let lens = format!(
        r#"{fov}<float name="aperture_radius" value="0"/><float name="focus_distance" value="1"/>"#
    );
    let a = render(&edge_scene("perspective", &fov, 2.5, true, 4), 4, 5);
    let b = load_xml(&edge_scene("thinlens", &lens, 2.5, true, 4), &[]);
    assert!(!b.scene.camera.has_lens());
    let b = render_loaded(&b, 4, 5);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        assert_eq!(p.sum.map(f64::to_bits), q.sum.map(f64::to_bits));
    }
}

/// Counts the draws a camera makes from its sampler.
struct Counting {
    draws: u32,
    moves: u32,
}

impl Sampler for Counting {
    fn next_1d(&mut self) -> f32 {
        self.draws += 1;
        0.5
    }
    fn start_dimension(&mut self, _dim: u32) {
        self.moves += 1;
    }
}

/// The pinhole and orthographic cameras draw nothing from the sampler (their images read the
/// dimensions they read before lenses existed); the thin lens draws its two values.
#[test]
fn only_the_thin_lens_draws_samples() {
    let fov = format!(r#"<float name="fov" value="{FOV}"/>"#);
    let lens = format!(r#"{fov}<float name="aperture_radius" value="0.1"/>"#);
    for (sensor, extra, draws) in [
        ("perspective", fov.as_str(), 0),
        ("orthographic", "", 0),
        ("thinlens", lens.as_str(), 2),
    ] {
        let l = load_xml(&edge_scene(sensor, extra, 2.0, true, 1), &[]);
        let mut s = Counting { draws: 0, moves: 0 };
        l.scene.camera.sample_ray(Vec2::new(3.5, 4.5), &mut s);
        assert_eq!((s.draws, s.moves), (draws, draws / 2), "{sensor}");
    }
}

/// An orthographic camera's rays are parallel to its axis and start on its near plane, on the
/// rectangle `[-1, 1] x [-1/aspect, 1/aspect]` scaled by `to_world`: every pixel meets a plane
/// facing it at the same distance.
#[test]
fn orthographic_rays_are_parallel_and_start_on_the_near_plane() {
    let xml = r#"<scene version="3.0.0">
  <sensor type="orthographic">
    <float name="near_clip" value="0.5"/>
    <float name="far_clip" value="20"/>
    <transform name="to_world"><scale value="2"/><translate x="1" y="-3" z="4"/></transform>
    <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="20"/></film>
  </sensor>
</scene>"#;
    let cam = load_xml(xml, &[]).scene.camera;
    let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
    for y in 0..=20 {
        for x in 0..=40 {
            let ray = cam.generate_ray(Vec2::new(x as f32, y as f32));
            assert_eq!(ray.d, Vec3::Z);
            // Near plane z = 0.5 in camera space: 4 + 2 * 0.5 in the world.
            assert!((ray.o.z - 5.0).abs() < 1e-6);
            assert!((ray.t_max - 19.5).abs() < 1e-5);
            // The plane z = 7 is 2 away from every origin.
            assert!(((7.0 - ray.o.z) / ray.d.z - 2.0).abs() < 1e-6);
            lo = lo.min(Vec2::new(ray.o.x, ray.o.y));
            hi = hi.max(Vec2::new(ray.o.x, ray.o.y));
        }
    }
    // Local x in [-1, 1] and y in [-1/2, 1/2] (aspect 2), scaled by 2 and moved by (1, -3).
    assert!(
        (lo - Vec2::new(-1.0, -4.0)).abs().max_element() < 1e-5,
        "{lo}"
    );
    assert!(
        (hi - Vec2::new(3.0, -2.0)).abs().max_element() < 1e-5,
        "{hi}"
    );
}

/// An emitting sphere of radius 1 seen by an orthographic camera whose `to_world` scales the
/// view by 2 covers `pi / 16` of the square image. Control: the fraction a view of scale 1
/// would give (`to_world`'s scale ignored) is rejected.
#[test]
fn orthographic_silhouette_has_the_radius_to_world_gives() {
    let spp = 16;
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="direct"/>
  <sensor type="orthographic">
    <transform name="to_world"><scale value="2"/><translate z="-5"/></transform>
    <film type="hdrfilm"><integer name="width" value="{RES}"/><integer name="height" value="{RES}"/><rfilter type="box"/></film>
    <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
  </sensor>
  <shape type="sphere">
    <float name="radius" value="1"/>
    <emitter type="area"><rgb name="radiance" value="1, 1, 1"/></emitter>
  </shape>
</scene>"#
    );
    let fb = render(&xml, spp, 6);
    // Rows are independent estimates of the covered fraction of their band; their mean over the
    // image is the covered fraction.
    let rows: Vec<f64> = (0..RES)
        .map(|y| (0..RES).map(|x| value(&fb, x, y)).sum::<f64>() / RES as f64)
        .collect();
    // Rows differ in expectation, so test the image mean with the per-pixel sample variance.
    let n = (RES * RES) as f64 * spp as f64;
    let m = mean(&rows);
    let var: f64 = fb
        .pixels
        .iter()
        .map(|p| p.sum_sq[0] / p.count as f64 - (p.sum[0] / p.count as f64).powi(2))
        .sum::<f64>()
        / (RES * RES) as f64
        * spp as f64
        / (spp as f64 - 1.0);
    let (expected, control) = (PI / 16.0, PI / 4.0);
    let p = t_test_f32(n, m, var, expected).1;
    let p_control = t_test_f32(n, m, var, control).1;
    println!("orthographic coverage {m:.4}, expected {expected:.4} (p = {p:.3}); control p = {p_control:.2e}");
    assert!(p >= alpha() && p_control < alpha());
}

/// The pixel index of a sharp edge along a line: the number of 0 pixels before the 1 pixels.
fn edge_position(fb: &Framebuffer, vertical: bool) -> f64 {
    let step = step_of(fb, vertical);
    let bright = step.iter().sum::<f64>();
    if step[0] == 0.0 {
        RES as f64 - bright
    } else {
        bright
    }
}

/// `principal_point_offset_x` 0.125 moves a vertical edge 8 pixels left (pixel x sees what
/// pixel x + 8 saw), `principal_point_offset_y` 0.25 a horizontal one 16 pixels up, on the
/// pinhole and on a thin lens focused on the edge. Control: the opposite shift is not what
/// renders.
#[test]
fn principal_point_offset_moves_the_image() {
    let fov = format!(r#"<float name="fov" value="{FOV}"/>"#);
    let lens = format!(
        r#"{fov}<float name="aperture_radius" value="0.3"/><float name="focus_distance" value="3"/>"#
    );
    for (sensor, base) in [("perspective", &fov), ("thinlens", &lens)] {
        for (vertical, name, offset, shift) in [
            (true, "principal_point_offset_x", 0.125, 8.0),
            (false, "principal_point_offset_y", 0.25, 16.0),
        ] {
            let plain = render(&edge_scene(sensor, base, 3.0, vertical, 4), 4, 8);
            let extra = format!(r#"{base}<float name="{name}" value="{offset}"/>"#);
            let moved = render(&edge_scene(sensor, &extra, 3.0, vertical, 4), 4, 8);
            let (e0, e1) = (
                edge_position(&plain, vertical),
                edge_position(&moved, vertical),
            );
            println!("{sensor} {name} {offset}: edge at {e0} -> {e1}");
            assert_eq!(e0, (RES / 2) as f64);
            assert_eq!(e1, e0 - shift, "{sensor} {name}");
            assert_ne!(e1, e0 + shift, "control: the opposite sign");
        }
    }
}

/// `shutter_open` and `shutter_close` are accepted on every sensor with a located warning;
/// a thin lens without an aperture, or focused at a non-positive distance, is a one-line
/// located error.
#[test]
fn shutter_warns_and_bad_lenses_are_located_errors() {
    let shutter =
        r#"<float name="shutter_open" value="0"/><float name="shutter_close" value="0.5"/>"#;
    let fov = format!(r#"<float name="fov" value="{FOV}"/>"#);
    for (sensor, extra) in [
        ("perspective", format!("{fov}{shutter}")),
        (
            "thinlens",
            format!(r#"{fov}<float name="aperture_radius" value="0.1"/>{shutter}"#),
        ),
        ("orthographic", shutter.to_string()),
    ] {
        let l = load_xml(&edge_scene(sensor, &extra, 2.0, true, 1), &[]);
        for name in ["shutter_open", "shutter_close"] {
            let w = l.warnings.iter().find(|w| w.contains(name));
            let w =
                w.unwrap_or_else(|| panic!("{sensor}: no warning for {name}: {:?}", l.warnings));
            assert!(
                w.contains("inline-test.xml:4:") && w.contains("ignored"),
                "{w}"
            );
        }
    }
    for (extra, what) in [
        (fov.clone(), "aperture_radius"),
        (
            format!(r#"{fov}<float name="aperture_radius" value="-1"/>"#),
            "aperture_radius",
        ),
        (
            format!(
                r#"{fov}<float name="aperture_radius" value="0.1"/><float name="focus_distance" value="0"/>"#
            ),
            "focus_distance",
        ),
    ] {
        let xml = edge_scene("thinlens", &extra, 2.0, true, 1);
        let e = tessera_scene::load_scene_str(&xml, std::path::Path::new("bad.xml"), &[])
            .map(|_| ())
            .expect_err("refused")
            .to_string();
        println!("{e}");
        assert!(
            e.starts_with("bad.xml:") && e.contains(what) && !e.contains('\n'),
            "{e}"
        );
    }
}

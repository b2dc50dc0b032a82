//! Chi-square goodness-of-fit tests of the direction sampling of the lights at infinity against
//! their own `pdf_environment`, and of the 2-D distribution behind the environment map.
//!
//! Each test draws 1e6 samples through the `tessera_lab::stats` harness with a fixed seed: test `k`
//! in the order of [`N_TESTS`]'s list uses seed `k`. The whole file fails with probability 1% if
//! every sampler is right: each test runs at `sidak_alpha(0.01, N_TESTS)`. Every result is
//! printed (`--nocapture` shows the p-values). Coordinates that bin the samples (cap squares,
//! latitude-longitude) are computed here in f64, independently of the core; each sampler's
//! `weight` is also checked against `eval_environment / pdf_environment` of its direction.

use std::f64::consts::{PI, TAU};
use tessera_core::math::{Frame, Norm};

use glam::{DMat3, DVec3, Vec2, Vec3};
use tessera_core::emitter::{DistantDisk, Emitter, EmitterCtx, EnvMap};
use tessera_core::geometry::Interaction;
use tessera_core::sampling::Distribution2D;
use tessera_core::Color;
use tessera_lab::stats::{sidak_alpha, Chi2Result, PlaneChi2, SphereChi2};
use tessera_tests::bsdf::assert_chi2_passes;
use tessera_tests::cap::{cap_coords, cap_dir, frame_around};

/// Number of chi-square tests in this file (one per seed):
///  1 Distribution2D on a grid with empty cells and an empty row,
///  2 distantdisk thetaA = 0.01 deg (rotated, cap square), 3 thetaA = 5 deg (cap square),
///  4 thetaA = 30 deg (sphere), 5 thetaA = 90 deg (rotated, sphere), 6 thetaA = 180 deg (sphere),
///  7 envmap with a bright patch and gradients (latitude-longitude square),
///  8 the same map rotated (latitude-longitude square), 9 a small rotated envmap (sphere),
/// 10 the map of 8 with MIS-compensated tables (latitude-longitude square).
const N_TESTS: usize = 10;

/// Samples per test.
const SAMPLES: usize = 1_000_000;

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// Prints the result and asserts that it passes at the corrected level.
fn check(name: &str, r: &Chi2Result) {
    assert_chi2_passes(name, r, N_TESTS);
}

/// A reference point for emitter sampling (lights at infinity ignore it).
fn origin() -> Interaction {
    Interaction {
        p: Vec3::ZERO,
        p_err: Vec3::ZERO,
        t: 1.0,
        ng: Vec3::Z,
        frame: Frame::from_normal(Vec3::Z),
        uv: Vec2::ZERO,
        shape: 0,
        wi: Vec3::Z,
    }
}

/// Samples `e` and checks the sample against the emitter's own `eval_environment` and
/// `pdf_environment`; counts the samples where they disagree.
struct Sampler<'a> {
    e: &'a Emitter,
    it: Interaction,
    mismatches: usize,
}

impl<'a> Sampler<'a> {
    fn new(e: &'a Emitter) -> Self {
        Sampler {
            e,
            it: origin(),
            mismatches: 0,
        }
    }
    fn sample(&mut self, u: Vec2) -> Option<Vec3> {
        let ctx = EmitterCtx {
            shapes: &[],
            disks: &[],
            scene_center: Vec3::ZERO,
            scene_radius: 1.0,
        };
        let s = self.e.sample(&ctx, &self.it, u)?;
        assert!(!s.delta && s.target.is_none());
        let pdf = self.e.pdf_environment(Vec3::ZERO, s.wo);
        let expect = self.e.eval_environment(s.wo) / pdf;
        let rel = ((s.weight - expect).abs() / expect.max(Color::splat(1e-30))).max_element();
        if !((s.pdf - pdf).abs() <= 1e-2 * pdf && rel <= 1e-2) {
            self.mismatches += 1;
            if self.mismatches < 6 {
                eprintln!(
                    "DEBUG u {u} wo {} spdf {} pdf {} w {} expect {}",
                    s.wo, s.pdf, pdf, s.weight, expect
                );
            }
        }
        Some(s.wo)
    }
    /// At most 1e-3 of the samples may disagree by more than 1%: f32 round-off in the direction
    /// is amplified at the edges of piecewise-constant densities, beside a bright patch (a
    /// jump of 400 over one pixel), and at the poles of a map, where the azimuth is
    /// ill-conditioned and the pixels of the top row (all at the pole) differ.
    fn check_consistent(&self, name: &str) {
        println!(
            "{name}: {} samples off eval/pdf by more than 1%",
            self.mismatches
        );
        assert!(
            self.mismatches <= SAMPLES / 1000,
            "{name}: {} samples whose weight or pdf disagree with eval_environment / \
             pdf_environment",
            self.mismatches
        );
    }
}

/// A rotation (f64) by `deg` degrees about `axis`.
fn rotation(axis: DVec3, deg: f64) -> DMat3 {
    DMat3::from_axis_angle(axis.unit(), deg.to_radians())
}

/// `1 - cos θ` of a half angle in degrees, in f64.
fn omc_deg(deg: f64) -> f64 {
    let s = (0.5 * deg.to_radians()).sin();
    2.0 * s * s
}

// ---------------------------------------------------------------------------------------------
// 1. The 2-D distribution
// ---------------------------------------------------------------------------------------------

#[test]
fn t01_distribution2d() {
    // 7 x 5 cells with empty cells and an empty row (row 2); the test grid has 2 x 2 bins per
    // cell, so the density is constant in every bin (exact cubature), and a sample carried over
    // a cell edge into an empty cell would fail at once.
    let (nx, ny) = (7usize, 5usize);
    #[rustfmt::skip]
    let w: [f32; 35] = [
        1.0, 0.0, 3.0, 0.5, 0.0, 8.0, 2.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 4.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        2.0, 2.0, 0.1, 9.0, 0.0, 1.0, 1.0,
        0.0, 5.0, 0.0, 0.0, 7.0, 0.0, 0.3,
    ];
    let total: f64 = w.iter().map(|&v| f64::from(v)).sum();
    let d = Distribution2D::new(&w, nx, ny).expect("a valid distribution");
    let r = PlaneChi2 {
        bins_x: 2 * nx,
        bins_y: 2 * ny,
        samples: SAMPLES,
    }
    .run(
        |u| d.sample(u).map(|(p, _)| p),
        |p| {
            // Reference density from the weights, in f64.
            let i = ((f64::from(p.x) * nx as f64) as usize).min(nx - 1);
            let j = ((f64::from(p.y) * ny as f64) as usize).min(ny - 1);
            f64::from(w[j * nx + i]) / total * (nx * ny) as f64
        },
        1,
    );
    check("Distribution2D 7x5 with empty cells", &r);
    // The density it reports is the one it samples.
    let mut rng = tessera_lab::stats::Pcg32::new(100);
    for _ in 0..10_000 {
        let (p, pdf) = d.sample(rng.next_vec2()).expect("a sample");
        assert_eq!(
            pdf,
            d.pdf(p),
            "Distribution2D::pdf disagrees with sample at {p}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 2-6. Distant disk
// ---------------------------------------------------------------------------------------------

/// A distant disk of half angle `deg` around `rot * +z`, binned in the cap square around its
/// axis with a 10% margin beyond the edge (which then crosses the middle of bin 18.18 of 20).
fn disk_cap_test(name: &str, deg: f64, rot: DMat3, seed: u64) {
    let e = Emitter::DistantDisk(DistantDisk::new(
        Color::new(1.0, 2.0, 3.0),
        deg as f32,
        rot.as_mat3(),
    ));
    let frame = frame_around(rot * DVec3::Z);
    let omc = omc_deg(deg);
    let omc_box = 1.1 * omc;
    let mut s = Sampler::new(&e);
    let r = PlaneChi2 {
        bins_x: 20,
        bins_y: 20,
        samples: SAMPLES,
    }
    .run(
        |u| s.sample(u).map(|d| cap_coords(d, &frame, omc_box)),
        |p| {
            let d = cap_dir(p, &frame, omc_box).as_vec3();
            f64::from(e.pdf_environment(Vec3::ZERO, d)) * TAU * omc_box
        },
        seed,
    );
    check(name, &r);
    s.check_consistent(name);
}

/// A distant disk of half angle `deg` around `rot * +z` on the whole sphere.
fn disk_sphere_test(name: &str, deg: f64, rot: DMat3, seed: u64) {
    let e = Emitter::DistantDisk(DistantDisk::new(
        Color::new(1.0, 2.0, 3.0),
        deg as f32,
        rot.as_mat3(),
    ));
    sphere_test(name, &e, seed);
}

/// `e`'s samples on the whole sphere (10 x 20 cells) against its `pdf_environment`, and each
/// sample against the emitter's own values.
fn sphere_test(name: &str, e: &Emitter, seed: u64) {
    let mut s = Sampler::new(e);
    let r = SphereChi2 {
        theta_bins: 10,
        phi_bins: 20,
        samples: SAMPLES,
    }
    .run(
        |u| s.sample(u),
        |d| f64::from(e.pdf_environment(Vec3::ZERO, d)),
        seed,
    );
    check(name, &r);
    s.check_consistent(name);
}

#[test]
fn t02_distant_disk_tiny() {
    // 1 - cos(0.01 deg) = 1.5e-8: far below f32's resolution of cos near 1.
    let rot = rotation(DVec3::new(1.0, -2.0, 0.5), 71.0);
    disk_cap_test("distantdisk thetaA = 0.01 deg, rotated", 0.01, rot, 2);
}

#[test]
fn t03_distant_disk_5() {
    let rot = rotation(DVec3::new(0.0, 1.0, 0.0), 40.0);
    disk_cap_test("distantdisk thetaA = 5 deg", 5.0, rot, 3);
}

#[test]
fn t04_distant_disk_30() {
    // The edge cos 30 = 0.866 lies at row 9.33 of 10.
    disk_sphere_test("distantdisk thetaA = 30 deg", 30.0, DMat3::IDENTITY, 4);
}

#[test]
fn t05_distant_disk_90_rotated() {
    // A hemisphere around a tilted axis: its edge is a great circle through many cells.
    let rot = rotation(DVec3::new(0.3, 1.0, -0.4), 57.0);
    disk_sphere_test("distantdisk thetaA = 90 deg, rotated", 90.0, rot, 5);
}

#[test]
fn t06_distant_disk_180() {
    disk_sphere_test("distantdisk thetaA = 180 deg", 180.0, DMat3::IDENTITY, 6);
}

// ---------------------------------------------------------------------------------------------
// 7-9. Environment map
// ---------------------------------------------------------------------------------------------

/// A `w x h` image with gradients in every channel, a bright 2x2 patch (radiance 400 against a
/// background of about 1) and a medium patch on the top row (the pole).
fn structured_image(w: usize, h: usize) -> Vec<[f32; 3]> {
    let mut px = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let (fx, fy) = (x as f32 / w as f32, y as f32 / h as f32);
            let mut c = [0.05 + 2.0 * fx, 0.1 + fy * fy, 0.02 + 0.5 * (1.0 - fy)];
            if (2 * w / 3..2 * w / 3 + 2).contains(&x) && (h / 3..h / 3 + 2).contains(&y) {
                c = [400.0, 300.0, 200.0];
            }
            if x == w / 5 && y == 0 {
                c = [20.0, 20.0, 20.0];
            }
            px.push(c);
        }
    }
    px
}

/// Latitude-longitude coordinates (Mitsuba 3's: `u = atan2(x, -z) / 2π`, `v = acos(y) / π`) of
/// a world direction, for a map rotated by `rot`; in f64.
fn latlong(d: Vec3, rot: &DMat3) -> Vec2 {
    let l = (rot.transpose() * d.as_dvec3()).unit();
    let mut u = l.x.atan2(-l.z) / TAU;
    if u < 0.0 {
        u += 1.0;
    }
    if u >= 1.0 {
        u -= 1.0;
    }
    let v = l.y.clamp(-1.0, 1.0).acos() / PI;
    Vec2::new(u as f32, v as f32)
}

/// Inverse of [`latlong`].
fn latlong_dir(p: Vec2, rot: &DMat3) -> DVec3 {
    let (phi, theta) = (TAU * f64::from(p.x), PI * f64::from(p.y));
    *rot * DVec3::new(
        phi.sin() * theta.sin(),
        theta.cos(),
        -phi.cos() * theta.sin(),
    )
}

/// An environment map sampled and binned in latitude-longitude coordinates, 2 x 2 bins per cell
/// of its distribution (cells join pixel centres: `u` edges at `(i + 1/2) / w`, `v` edges at
/// `j / (h - 1)`), so the density is constant in every bin. On the square the solid-angle
/// density becomes `pdf · 2π² sin θ`.
/// With `compensated`, the map samples by its MIS-compensated tables (zero density wherever
/// the four pixels of a cell are dimmer than the map's mean).
fn envmap_latlong_test(name: &str, w: usize, h: usize, rot: DMat3, seed: u64, compensated: bool) {
    let mut env =
        EnvMap::new(structured_image(w, h), w, h, 1.5, rot.as_mat3()).expect("a valid map");
    assert_eq!(env.set_compensated(compensated), compensated, "{name}");
    let e = Emitter::EnvMap(env);
    let mut s = Sampler::new(&e);
    let r = PlaneChi2 {
        bins_x: 2 * w,
        bins_y: 2 * (h - 1),
        samples: SAMPLES,
    }
    .run(
        |u| s.sample(u).map(|d| latlong(d, &rot)),
        |p| {
            let d = latlong_dir(p, &rot).as_vec3();
            let sin_t = (PI * f64::from(p.y)).sin();
            f64::from(e.pdf_environment(Vec3::ZERO, d)) * 2.0 * PI * PI * sin_t
        },
        seed,
    );
    check(name, &r);
    s.check_consistent(name);
}

#[test]
fn t07_envmap_latlong() {
    envmap_latlong_test(
        "envmap 48x25 (latitude-longitude)",
        48,
        25,
        DMat3::IDENTITY,
        7,
        false,
    );
}

#[test]
fn t08_envmap_latlong_rotated() {
    let rot = rotation(DVec3::new(0.2, 1.0, 0.7), 113.0);
    envmap_latlong_test(
        "envmap 30x17 rotated (latitude-longitude)",
        30,
        17,
        rot,
        8,
        false,
    );
}

#[test]
fn t10_envmap_latlong_compensated() {
    let rot = rotation(DVec3::new(0.2, 1.0, 0.7), 113.0);
    let name = "envmap 30x17 rotated, compensated (latitude-longitude)";
    envmap_latlong_test(name, 30, 17, rot, 10, true);
    // The compensated density is zero where the map is dim and larger where it is bright: a
    // direction towards the darkest pixel has density zero with it and not without it.
    let img = structured_image(30, 17);
    let lum = |p: &[f32; 3]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    let k = (0..img.len())
        .filter(|k| (2..15).contains(&(k / 30)))
        .min_by(|&a, &b| lum(&img[a]).total_cmp(&lum(&img[b])))
        .expect("pixels");
    let d = latlong_dir(
        Vec2::new(((k % 30) as f32 + 0.5) / 30.0, (k / 30) as f32 / 16.0),
        &rot,
    )
    .as_vec3();
    let mut env = EnvMap::new(img, 30, 17, 1.5, rot.as_mat3()).expect("a valid map");
    let plain = Emitter::EnvMap(env.clone()).pdf_environment(Vec3::ZERO, d);
    assert!(env.set_compensated(true));
    let comp = Emitter::EnvMap(env.clone()).pdf_environment(Vec3::ZERO, d);
    assert!(
        plain > 0.0 && comp == 0.0,
        "plain {plain}, compensated {comp}"
    );
    // Turned off again, the plain tables come back exactly.
    assert!(!env.set_compensated(false));
    assert_eq!(Emitter::EnvMap(env).pdf_environment(Vec3::ZERO, d), plain);
}

#[test]
fn t09_envmap_sphere() {
    // The sphere harness's own cells (uniform in cos θ about +z, φ from +x): the map's cell
    // edges cross them, so the cubature refines along them; a small map keeps that cheap.
    let rot = rotation(DVec3::new(1.0, 0.3, 0.2), 64.0);
    let (w, h) = (6, 4);
    let env = EnvMap::new(structured_image(w, h), w, h, 1.0, rot.as_mat3()).expect("a valid map");
    sphere_test("envmap 6x4 rotated (sphere)", &Emitter::EnvMap(env), 9);
}

/// The tests have power (not counted in [`N_TESTS`]: it must fail): samples of a 30 degree disk
/// against the density of a 30.3 degree one (a valid pdf, 2% too low on the disk) are rejected.
#[test]
fn control_rejects_a_two_percent_wrong_pdf() {
    let e = Emitter::DistantDisk(DistantDisk::new(
        Color::ONE,
        30.0,
        DMat3::IDENTITY.as_mat3(),
    ));
    let mut s = Sampler::new(&e);
    let omc = omc_deg(30.3);
    let r = SphereChi2 {
        // Rows 0.01 wide in cos θ: the cap spans 13.4 of them, the edges cross rows 186.6
        // (30 deg) and 186.3 (30.3 deg).
        theta_bins: 200,
        phi_bins: 4,
        samples: SAMPLES,
    }
    .run(
        |u| s.sample(u),
        |d| {
            if 1.0 - f64::from(d.z) <= omc {
                1.0 / (TAU * omc)
            } else {
                0.0
            }
        },
        100,
    );
    println!("control (30 deg disk vs 30.3 deg pdf): {r}");
    assert!(!r.passes(alpha()), "a 2% wrong pdf passed: {r}");
}

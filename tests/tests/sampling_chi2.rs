//! Chi-square goodness-of-fit tests of every sampling routine of the core against its pdf.
//!
//! Each test draws its samples through the `tessera_lab::stats` harness (`SphereChi2`,
//! `PlaneChi2`, or `chi2_test` on counts drawn from a `Pcg32`), with a fixed seed: test `k` in
//! the order of [`N_TESTS`]'s list uses seed `k`. The whole file fails with probability 1% if
//! every sampler is right: each test runs at the Šidák-corrected level
//! `sidak_alpha(0.01, N_TESTS)`. Every result is printed (run with `--nocapture` to see the
//! p-values) and is the assert message on failure.
//!
//! Reference densities are written here independently of the core where that is meaningful
//! (mesh and disk ray casts in f64, the Gaussian filter's step table, the discrete pmf); the
//! core's own pdf functions are what is under test otherwise.

use std::f64::consts::TAU;
use tessera_core::math::{Norm, Ray, Transform};

use glam::{DMat4, DVec2, DVec3, Vec2, Vec3};
use tessera_core::camera::{Filter, GaussianFilter, LanczosFilter, MitchellFilter, TentFilter};
use tessera_core::geometry::{Disk, Mesh, Shape, ShapeKind, Sphere};
use tessera_core::sampling::{warp, Discrete1D};
use tessera_lab::stats::{
    chi2_test, sidak_alpha, Chi2Result, Pcg32, PlaneChi2, SphereChi2, DEFAULT_MIN_EXPECTED,
};
use tessera_tests::bsdf::assert_chi2_passes;
use tessera_tests::cap::{cap_coords, cap_dir, frame_around};
use tessera_tests::filter_reference::{lanczos, mitchell};

/// Number of chi-square tests in this file (one per seed):
///  1 uniform sphere, 2 cosine hemisphere, 3-5 uniform cone (cos_max 0.9, 0, -0.5),
///  6 tiny cone (omc), 7 concentric disk, 8 triangle barycentrics,
///  9 sphere cone far, 10 sphere cone near, 11 mesh directions, 12 mesh triangle choice,
///  13 mesh barycentrics in one triangle, 14 ellipse (disk) directions,
///  15 Discrete1D indices, 16 Discrete1D rescaled u, 17 box filter, 18 Gaussian filter,
///  19 tent filter, 20 Mitchell filter, 21 Lanczos filter, 22 rectangle (parallelogram)
///  directions.
const N_TESTS: usize = 22;

/// Samples per test.
const SAMPLES: usize = 1_000_000;

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// Prints the result and asserts that it passes at the corrected level.
fn check(name: &str, r: &Chi2Result) {
    assert_chi2_passes(name, r, N_TESTS);
}

// ---------------------------------------------------------------------------------------------
// Helpers: frames and the "cap square" map
// ---------------------------------------------------------------------------------------------

/// `1 - cos` of the half-angle of the cone subtended by a sphere of radius `radius` at
/// distance `dist`, in f64.
fn sphere_omc(radius: f64, dist: f64) -> f64 {
    let sin2 = (radius / dist).powi(2);
    sin2 / (1.0 + (1.0 - sin2).sqrt())
}

// ---------------------------------------------------------------------------------------------
// 1. Warps
// ---------------------------------------------------------------------------------------------

#[test]
fn t01_uniform_sphere() {
    let r = SphereChi2::default().run(
        |u| Some(warp::square_to_uniform_sphere(u)),
        |_| f64::from(warp::uniform_sphere_pdf()),
        1,
    );
    check("uniform sphere", &r);
}

#[test]
fn t02_cosine_hemisphere() {
    let r = SphereChi2::default().run(
        |u| Some(warp::square_to_cosine_hemisphere(u)),
        |v| f64::from(warp::cosine_hemisphere_pdf(v)),
        2,
    );
    check("cosine hemisphere", &r);
}

/// The cone's edge `cos θ = cos_max` must not coincide with a cell boundary in `cos θ` when
/// f32 round-off can put a sample a hair outside it (it would land in a cell of expectation
/// 0); `theta_bins` are chosen so the edge crosses the middle of a row, except for
/// `cos_max = 0` where the sampled `cos θ = 1 - u` is at least `2^-24 > 0` and the edge on a
/// row boundary makes any sample below the horizon an immediate failure.
fn cone_test(cos_max: f32, theta_bins: usize, seed: u64) -> Chi2Result {
    SphereChi2 {
        theta_bins,
        phi_bins: 20,
        samples: SAMPLES,
    }
    .run(
        |u| Some(warp::square_to_uniform_cone(u, cos_max)),
        |v| f64::from(warp::uniform_cone_pdf(v, cos_max)),
        seed,
    )
}

#[test]
fn t03_uniform_cone_0_9() {
    // Rows of width 2/205 in cos θ: the edge 0.9 sits at 194.75 rows, the cone spans ~10 rows.
    check("uniform cone cos_max = 0.9", &cone_test(0.9, 205, 3));
}

#[test]
fn t04_uniform_cone_0() {
    check("uniform cone cos_max = 0", &cone_test(0.0, 10, 4));
}

#[test]
fn t05_uniform_cone_minus_0_5() {
    // Edge at row 2.5 of 10.
    check("uniform cone cos_max = -0.5", &cone_test(-0.5, 10, 5));
}

#[test]
fn t06_uniform_cone_omc_tiny() {
    // A cone of 1 - cos θ_max = 1e-3 (θ_max ≈ 2.6°) is a single cell of any reasonable sphere
    // grid, so the cap alone is binned: `cap_coords` maps it to [0, 1/1.1] × [0, 1) of the
    // square with cells of equal solid angle, and the 10% margin beyond the edge (which then
    // crosses the middle of column 18.18 of 20) catches samples outside the cone. The claimed
    // density is 1 / (2π omc) on the cap (the value `Sphere::cone_pdf` pairs with this warp;
    // there is no separate pdf function for it), i.e. 2π omc_box / (2π omc) = 1.1 on the square.
    let omc = 1e-3f32;
    let omc64 = f64::from(omc);
    let omc_box = 1.1 * omc64;
    let frame = [DVec3::X, DVec3::Y, DVec3::Z];
    let r = PlaneChi2 {
        bins_x: 20,
        bins_y: 20,
        samples: SAMPLES,
    }
    .run(
        |u| {
            let v = warp::square_to_uniform_cone_omc(u, omc);
            Some(cap_coords(v, &frame, omc_box))
        },
        |p| {
            if f64::from(p.x) * omc_box <= omc64 {
                TAU * omc_box / (TAU * omc64)
            } else {
                0.0
            }
        },
        6,
    );
    check("uniform cone omc = 1e-3 (cap square)", &r);
}

#[test]
fn t07_concentric_disk() {
    // [-1,1]^2 mapped to [0,1]^2 by p = (d + 1) / 2: the area density is scaled by 4.
    let r = PlaneChi2 {
        bins_x: 20,
        bins_y: 20,
        samples: SAMPLES,
    }
    .run(
        |u| Some((warp::square_to_uniform_disk_concentric(u) + Vec2::ONE) * 0.5),
        |p| 4.0 * f64::from(warp::uniform_disk_pdf(2.0 * p - Vec2::ONE)),
        7,
    );
    check("concentric disk", &r);
}

#[test]
fn t08_uniform_triangle() {
    let r = PlaneChi2::default().run(
        |u| Some(warp::square_to_uniform_triangle(u)),
        |b| f64::from(warp::uniform_triangle_pdf(b)),
        8,
    );
    check("uniform triangle (b1, b2)", &r);
}

// ---------------------------------------------------------------------------------------------
// 2. Sphere cone sampling (as the area emitter uses it)
// ---------------------------------------------------------------------------------------------

/// Checks one cone sample: `p` on the sphere, `n` its outward unit normal, on the side facing
/// `r`, and the pdf equal to `cone_pdf`.
fn check_cone_sample(s: &Sphere, r: Vec3, p: Vec3, n: Vec3, pdf: f32, cone_pdf: f32) {
    let radius = f64::from(s.radius);
    let dist = (p - s.center).as_dvec3().norm();
    assert!(
        (dist - radius).abs() <= 1e-5 * radius,
        "sampled p = {p} is at distance {dist} from the centre, radius {radius}"
    );
    let nn = n.as_dvec3();
    assert!((nn.norm() - 1.0).abs() <= 1e-5, "normal {n} is not unit");
    let outward = (p - s.center).as_dvec3() / dist;
    assert!(
        nn.dot(outward) >= 1.0 - 1e-5,
        "normal {n} is not outward at {p}"
    );
    // The visible side: the normal faces r (up to round-off on the silhouette).
    let to_r = (r - p).as_dvec3();
    assert!(
        nn.dot(to_r) >= -1e-4 * to_r.norm(),
        "sampled p = {p} is on the far side of the sphere from {r}"
    );
    assert_eq!(pdf, cone_pdf, "sample_cone's pdf differs from cone_pdf");
}

/// Whether the ray from `r` along `d` hits the sphere (core's intersection routine).
fn hits_sphere(s: &Sphere, r: Vec3, d: DVec3) -> bool {
    s.intersect(&Ray::new(r, d.as_vec3()), f32::INFINITY)
        .is_some()
}

#[test]
fn t09_sphere_cone_far() {
    // Distance 100 radii: the cone has 1 - cos θ_max ≈ 5e-5 (3e-4 sr), far too small for a
    // sphere grid, so it is binned on the cap square around the axis r -> centre (see
    // `cap_coords`, same construction as t06), with a 10% margin in 1 - cos θ.
    let s = Sphere {
        center: Vec3::new(0.7, -1.3, 2.1),
        radius: 0.25,
    };
    // Axis with a negative z component (the other branch of the core's frame construction).
    let axis = DVec3::new(-0.3, 0.45, -1.0).unit();
    let r = (s.center.as_dvec3() - axis * 100.0 * f64::from(s.radius)).as_vec3();
    let axis = (s.center - r).as_dvec3().unit();
    let frame = frame_around(axis);
    let dist = (s.center - r).as_dvec3().norm();
    let omc_box = 1.1 * sphere_omc(f64::from(s.radius), dist);
    let cone_pdf = s.cone_pdf(r).expect("r is outside");

    let result = PlaneChi2 {
        bins_x: 20,
        bins_y: 20,
        samples: SAMPLES,
    }
    .run(
        |u| {
            let cs = s.sample_cone(r, u)?;
            check_cone_sample(&s, r, cs.p, cs.n, cs.pdf, cone_pdf);
            Some(cap_coords((cs.p - r).unit(), &frame, omc_box))
        },
        |p| {
            if hits_sphere(&s, r, cap_dir(p, &frame, omc_box)) {
                f64::from(cone_pdf) * TAU * omc_box
            } else {
                0.0
            }
        },
        9,
    );
    check("sphere cone, distance 100 radii (cap square)", &result);
}

#[test]
fn t10_sphere_cone_near() {
    // Distance 1.5 radii: the cone (half-angle 41.8°, 1.6 sr) is binned with SphereChi2 after
    // rotating the axis r -> centre onto +z (our own frame): the cone's edge
    // cos θ_max = sqrt(1 - 1/2.25) = 0.7454 then crosses row 69.8 of 80 instead of cutting
    // cells obliquely, where thin slivers could escape the cubature.
    let s = Sphere {
        center: Vec3::new(0.3, -0.2, 0.5),
        radius: 0.8,
    };
    let axis = DVec3::new(0.5, 0.8, 0.35).unit();
    let r = (s.center.as_dvec3() - axis * 1.5 * f64::from(s.radius)).as_vec3();
    let axis = (s.center - r).as_dvec3().unit();
    let frame = frame_around(axis);
    let cone_pdf = s.cone_pdf(r).expect("r is outside");

    let result = SphereChi2 {
        theta_bins: 80,
        phi_bins: 40,
        samples: SAMPLES,
    }
    .run(
        |u| {
            let cs = s.sample_cone(r, u)?;
            check_cone_sample(&s, r, cs.p, cs.n, cs.pdf, cone_pdf);
            let d = (cs.p - r).as_dvec3().unit();
            Some(DVec3::new(d.dot(frame[0]), d.dot(frame[1]), d.dot(frame[2])).as_vec3())
        },
        |l| {
            let l = l.as_dvec3();
            let d = frame[0] * l.x + frame[1] * l.y + frame[2] * l.z;
            if hits_sphere(&s, r, d) {
                f64::from(cone_pdf)
            } else {
                0.0
            }
        },
        10,
    );
    check("sphere cone, distance 1.5 radii", &result);
}

#[test]
fn sphere_cone_inside_is_none() {
    let s = Sphere {
        center: Vec3::new(1.0, 2.0, -3.0),
        radius: 2.0,
    };
    let inside = [
        s.center,
        s.center + Vec3::new(0.5, -1.0, 0.7),
        s.center + Vec3::new(0.0, 0.0, 1.999),
    ];
    for r in inside {
        assert!(s.cone_pdf(r).is_none(), "cone_pdf from inside point {r}");
        for u in [
            Vec2::new(0.0, 0.0),
            Vec2::new(0.3, 0.7),
            Vec2::new(0.999, 0.5),
        ] {
            assert!(
                s.sample_cone(r, u).is_none(),
                "sample_cone from inside point {r}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 3. Shape-level sampling (area lights): meshes and disks
// ---------------------------------------------------------------------------------------------
//
// Why the geometry below is special. The harness computes a cell's expected count by adaptive
// cubature and fails at once if a sample lands in a cell whose expected count came out 0. When
// a shape's outline merely clips a cell (a corner, or a thin sliver along a cell edge), the
// cubature's nodes can all miss it and report 0 although a few samples are due there: a
// spurious "impossible sample" failure that depends on the sampler's exact output. (With five
// generic triangles on a 20 × 40 grid, ~20 such cells existed, and one of them did catch a
// sample.) So the outlines are made to cross cells through their middles:
// - the mesh is made of "wedge" triangles: an apex straight above (or below) the reference
//   point and a base in the horizontal plane through it. Seen from `r`, such a triangle is
//   exactly the rectangle `φ1 <= φ <= φ2`, `cos θ >= 0` (or `<= 0`) in SphereChi2's
//   coordinates; `φ1`, `φ2` are put in the middle of phi cells, and the horizon in the middle
//   of a theta row (odd number of rows). The density inside (area-to-solid-angle Jacobian) is
//   far from uniform, and the triangles differ in distance, tilt and area (factor ~300).
// - the ellipse is seen from a point of its focal hyperbola, from where the cone over it is a
//   right circular cone (checked below); binned after rotating that cone's axis onto +z, its
//   outline is a circle of constant cos θ, put in the middle of a row.

/// Reference point of the mesh tests.
const MESH_REF: Vec3 = Vec3::new(0.1, 0.2, -0.3);

/// The sphere grid of the mesh direction test: an odd number of rows puts the horizon in the
/// middle of a row.
const MESH_GRID: (usize, usize) = (11, 20);

/// A wedge triangle relative to the reference point: apex at height `h` on the vertical
/// through it, base corners at horizontal distances `d1`, `d2` in the azimuths of phi cells
/// `c1`, `c2` (fractional cell indices of `MESH_GRID`, put at cell centres).
fn wedge(h: f32, c1: f32, d1: f32, c2: f32, d2: f32) -> [Vec3; 3] {
    assert!(
        MESH_GRID.0 % 2 == 1,
        "the horizon must cross the middle of a row"
    );
    assert!(
        c1.fract() == 0.5 && c2.fract() == 0.5,
        "wedge edges must cross the middle of phi cells"
    );
    let cell = std::f32::consts::TAU / MESH_GRID.1 as f32;
    let (p1, p2) = (c1 * cell, c2 * cell);
    [
        Vec3::new(0.0, 0.0, h),
        Vec3::new(d1 * p1.cos(), d1 * p1.sin(), 0.0),
        Vec3::new(d2 * p2.cos(), d2 * p2.sin(), 0.0),
    ]
}

/// Five wedge triangles (world space) around [`MESH_REF`], none overlapping another as seen
/// from it (three above the horizon in disjoint azimuth ranges, two below), of very different
/// areas, none coplanar with another; the winding makes each face the reference point.
fn test_triangles() -> Vec<[Vec3; 3]> {
    let rel = [
        wedge(2.5, 0.5, 3.0, 4.5, 2.2),    // large, above
        wedge(0.25, 6.5, 0.3, 7.5, 0.2),   // tiny and close, above
        wedge(1.2, 10.5, 1.0, 13.5, 1.6),  // medium, above
        wedge(-0.8, 2.5, 1.5, 8.5, 2.5),   // below
        wedge(-2.0, 11.5, 0.7, 16.5, 1.1), // below, steep
    ];
    rel.iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| v + MESH_REF);
            // Counter-clockwise seen from the reference point.
            if (b - a).cross(c - a).dot(MESH_REF - a) >= 0.0 {
                [a, b, c]
            } else {
                [a, c, b]
            }
        })
        .collect()
}

/// The mesh of [`test_triangles`], with per-vertex shading normals that differ from the
/// geometric normals (the densities must use the geometric ones).
fn test_mesh() -> Mesh {
    let tris = test_triangles();
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut indices = Vec::new();
    for (i, t) in tris.iter().enumerate() {
        let ng = (t[1] - t[0]).cross(t[2] - t[0]).unit();
        for (k, &p) in t.iter().enumerate() {
            positions.push(p);
            let tilt = Vec3::new(0.3 * k as f32, -0.2, 0.25 * i as f32);
            normals.push((ng + tilt).unit());
        }
        let base = 3 * i as u32;
        indices.push([base, base + 1, base + 2]);
    }
    Mesh::new(positions, normals, Vec::new(), indices)
}

/// Area of a triangle in f64.
fn tri_area64(t: &[Vec3; 3]) -> f64 {
    let [a, b, c] = t.map(|v| v.as_dvec3());
    0.5 * (b - a).cross(c - a).norm()
}

/// A triangle prepared for ray casts from a fixed origin (f64, independent of the core's
/// intersection routine): the ray along `d` meets it iff `d` is on the same side of the three
/// planes through the origin and an edge, and the plane is ahead.
struct TriangleFromPoint {
    q0: DVec3,
    edges: [DVec3; 3],
    n: DVec3,
}

impl TriangleFromPoint {
    fn new(r: DVec3, t: &[Vec3; 3]) -> Self {
        let [q0, q1, q2] = t.map(|v| v.as_dvec3() - r);
        TriangleFromPoint {
            q0,
            edges: [q0.cross(q1), q1.cross(q2), q2.cross(q0)],
            n: (q1 - q0).cross(q2 - q0),
        }
    }

    /// The hit point, relative to the origin, of the ray along `d`.
    fn hit(&self, d: DVec3) -> Option<DVec3> {
        let e = self.edges.map(|e| d.dot(e));
        let inside = e.iter().all(|&x| x >= 0.0) || e.iter().all(|&x| x <= 0.0);
        if !inside {
            return None;
        }
        let dn = d.dot(self.n);
        if dn == 0.0 {
            return None;
        }
        let t = self.q0.dot(self.n) / dn;
        (t > 0.0).then(|| d * t)
    }
}

/// Each triangle of `tris` prepared for f64 casts from `r`, with the mesh's normal of it.
fn casts_from(r: Vec3, tris: &[[Vec3; 3]], mesh: &Mesh) -> Vec<(TriangleFromPoint, Vec3)> {
    tris.iter()
        .enumerate()
        .map(|(i, t)| (TriangleFromPoint::new(r.as_dvec3(), t), mesh.face_normal(i)))
        .collect()
}

/// Chi-square of the directions from `r` of light samples on `mesh` (each sample's density
/// checked against `pdf_from` on the way) against the solid-angle density `density`.
fn mesh_directions_chi2(
    shape: &Shape,
    r: Vec3,
    density: impl Fn(Vec3) -> f64,
    seed: u64,
) -> Chi2Result {
    SphereChi2 {
        theta_bins: MESH_GRID.0,
        phi_bins: MESH_GRID.1,
        samples: SAMPLES,
    }
    .run(
        |u| {
            let (ps, pdf) = shape.sample_from(r, u, &[])?;
            let want = shape.pdf_from(r, ps.p, ps.ng, &[]);
            assert!(
                (pdf - want).abs() <= 1e-5 * want,
                "sample_from pdf {pdf} vs pdf_from {want} at {}",
                ps.p
            );
            Some((ps.p - r).as_dvec3().unit().as_vec3())
        },
        density,
        seed,
    )
}

/// `mesh` as a shape of its own.
fn mesh_shape(mesh: Mesh) -> Shape {
    Shape {
        kind: ShapeKind::Mesh(mesh),
        bsdf: 0,
        emitter: None,
        flip_normals: false,
    }
}

#[test]
fn t11_mesh_directions() {
    let mesh = test_mesh();
    let tris = test_triangles();
    let r = MESH_REF;
    let r64 = r.as_dvec3();
    let casts = casts_from(r, &tris, &mesh);
    let shape = mesh_shape(mesh);
    let overlaps = std::cell::Cell::new(0usize);
    let result = mesh_directions_chi2(
        &shape,
        r,
        |w| {
            // Sum over the triangles the ray meets (all of them: that is the density of the
            // sampler's directions; no two overlap as seen from r, which is checked, so this
            // is also the first-hit density an emitter would evaluate).
            let d = w.as_dvec3();
            let mut pdf = 0.0;
            let mut hits = 0;
            for (tri, ng) in &casts {
                if let Some(q) = tri.hit(d) {
                    hits += 1;
                    pdf += f64::from(shape.pdf_from(r, (r64 + q).as_vec3(), *ng, &[]));
                }
            }
            if hits > 1 {
                overlaps.set(overlaps.get() + 1);
            }
            pdf
        },
        11,
    );
    assert_eq!(overlaps.get(), 0, "triangles overlap as seen from r");
    check("mesh directions (5 triangles)", &result);
}

#[test]
fn t12_mesh_triangle_choice() {
    let mesh = test_mesh();
    let tris = test_triangles();
    let areas: Vec<f64> = tris.iter().map(tri_area64).collect();
    let total: f64 = areas.iter().sum();
    let mut rng = Pcg32::new(12);
    let mut observed = vec![0.0; tris.len()];
    for _ in 0..SAMPLES {
        let (i, b1, b2) = mesh.sample(rng.next_vec2()).expect("mesh has area");
        assert!(
            b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0 + 1e-6,
            "({b1}, {b2})"
        );
        observed[i] += 1.0;
    }
    let expected: Vec<f64> = areas.iter().map(|a| SAMPLES as f64 * a / total).collect();
    println!("triangle areas {areas:?}, counts {observed:?}");
    check(
        "mesh triangle choice by area",
        &chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED),
    );
}

#[test]
fn t13_mesh_barycentrics_in_one_triangle() {
    // Barycentrics of the samples that land in triangle 2 (a middle interval of the area cdf,
    // so the reuse of u.x matters); the others count as failures, and the pdf integrates to
    // the triangle's probability area_2 / total.
    let k = 2;
    let mesh = test_mesh();
    let tris = test_triangles();
    let total: f64 = tris.iter().map(tri_area64).sum();
    let prob = tri_area64(&tris[k]) / total;
    let r = PlaneChi2::default().run(
        |u| {
            let (i, b1, b2) = mesh.sample(u)?;
            (i == k).then_some(Vec2::new(b1, b2))
        },
        |b| {
            let (b1, b2) = (f64::from(b.x), f64::from(b.y));
            if b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0 {
                2.0 * prob
            } else {
                0.0
            }
        },
        13,
    );
    check("mesh barycentrics in triangle 2", &r);
}

#[test]
fn t14_disk_ellipse_directions() {
    // The ellipse x²/a² + y²/b² <= 1 (a = 2, b = 0.8) of its own frame, seen from the point
    // (x, 0, h) of its focal hyperbola x²/(a² - b²) - z²/b² = 1 at height h = 0.3 (above the
    // ellipse, near its tip): from there the cone over the ellipse is a right circular cone.
    // The disk's transform is the unit disk rotated in its plane (so the parametrization is a
    // general affine map, not just a scale), scaled by (a, b, 1.5), then tilted and moved.
    let (a, b, h) = (2.0f64, 0.8f64, 0.3f64);
    let x = ((a * a - b * b) * (1.0 + h * h / (b * b))).sqrt();
    let place = DMat4::from_translation(DVec3::new(0.3, -0.2, -1.5))
        * DMat4::from_axis_angle(DVec3::new(1.0, 0.5, 0.0).unit(), 0.6);
    let m =
        (place * DMat4::from_scale(DVec3::new(a, b, 1.5)) * DMat4::from_rotation_z(0.7)).as_mat4();
    let r = place.transform_point3(DVec3::new(x, 0.0, h)).as_vec3();
    let disk = Disk::new(Transform::new(m).expect("invertible")).expect("disk has area");
    let disks = [disk];
    let shape = Shape {
        kind: ShapeKind::Disk(0),
        bsdf: 0,
        emitter: None,
        flip_normals: false,
    };
    // All further geometry from the f32 data the core sees.
    let r64 = r.as_dvec3();
    let m64: DMat4 = m.as_dmat4();
    let inv64 = m64.inverse();
    let o_local = inv64.transform_point3(r64);
    assert!(o_local.z > 0.1, "the reference point is above the disk");

    // The cone's axis: normal of the plane through the tips of three unit rim directions.
    let rim = |t: f64| (m64.transform_point3(DVec3::new(t.cos(), t.sin(), 0.0)) - r64).unit();
    let (u0, u1, u2) = (rim(0.0), rim(TAU / 3.0), rim(2.0 * TAU / 3.0));
    let mut axis = (u1 - u0).cross(u2 - u0).unit();
    if axis.dot(u0) < 0.0 {
        axis = -axis;
    }
    let cos_max = axis.dot(u0);
    for k in 0..720 {
        let c = axis.dot(rim(TAU * k as f64 / 720.0));
        assert!(
            (c - cos_max).abs() < 1e-6,
            "the cone over the ellipse is not circular: {c} vs {cos_max}"
        );
    }
    let theta_bins = 40;
    let row = 0.5 * (cos_max + 1.0) * theta_bins as f64;
    assert!(
        (0.25..0.75).contains(&row.fract()),
        "cone edge cos = {cos_max} at row {row}: too close to a row boundary"
    );
    let frame = frame_around(axis);

    let result = SphereChi2 {
        theta_bins,
        phi_bins: 20,
        samples: SAMPLES,
    }
    .run(
        |u| {
            let (ps, pdf) = shape.sample_from(r, u, &disks)?;
            let local = inv64.transform_point3(ps.p.as_dvec3());
            assert!(
                local.z.abs() < 1e-5 && local.x.hypot(local.y) <= 1.0 + 1e-5,
                "sampled point {} is not on the disk (local {local})",
                ps.p
            );
            let want = shape.pdf_from(r, ps.p, ps.ng, &disks);
            assert!(
                (pdf - want).abs() <= 1e-5 * want,
                "sample_from pdf {pdf} vs pdf_from {want}"
            );
            let d = (ps.p - r).as_dvec3().unit();
            Some(DVec3::new(d.dot(frame[0]), d.dot(frame[1]), d.dot(frame[2])).as_vec3())
        },
        |l| {
            // Back to world, then a ray cast in the disk's local frame, f64.
            let l = l.as_dvec3();
            let w = frame[0] * l.x + frame[1] * l.y + frame[2] * l.z;
            let d = inv64.transform_vector3(w);
            if d.z == 0.0 {
                return 0.0;
            }
            let t = -o_local.z / d.z;
            let (x, y) = (o_local.x + t * d.x, o_local.y + t * d.y);
            if t > 0.0 && x * x + y * y <= 1.0 {
                let p = m64.transform_point3(DVec3::new(x, y, 0.0));
                f64::from(shape.pdf_from(r, p.as_vec3(), disk.normal, &disks))
            } else {
                0.0
            }
        },
        14,
    );
    println!(
        "ellipse: cone half-angle {:.2} deg",
        cos_max.acos().to_degrees()
    );
    check("ellipse (disk) directions", &result);
}

// ---------------------------------------------------------------------------------------------
// 4. Discrete1D
// ---------------------------------------------------------------------------------------------

/// Weights with zeros first, in a run, and last.
const WEIGHTS: [f32; 10] = [0.0, 3.0, 0.5, 0.0, 0.0, 1.25, 7.0, 0.05, 2.0, 0.0];

fn reference_pmf() -> Vec<f64> {
    let total: f64 = WEIGHTS.iter().map(|&w| f64::from(w)).sum();
    WEIGHTS.iter().map(|&w| f64::from(w) / total).collect()
}

#[test]
fn t15_discrete_indices() {
    let dist = Discrete1D::new(WEIGHTS).expect("valid weights");
    let pmf = reference_pmf();
    for (i, &p) in pmf.iter().enumerate() {
        assert!(
            (f64::from(dist.pmf(i)) - p).abs() <= 1e-6,
            "pmf({i}) = {} vs {p}",
            dist.pmf(i)
        );
    }
    let mut rng = Pcg32::new(15);
    let mut observed = vec![0.0; WEIGHTS.len()];
    for _ in 0..SAMPLES {
        let (i, ur) = dist.sample_reuse(rng.next_f32());
        assert!((0.0..1.0).contains(&ur), "u rescaled = {ur}");
        observed[i] += 1.0;
    }
    for (i, &w) in WEIGHTS.iter().enumerate() {
        assert!(
            w > 0.0 || observed[i] == 0.0,
            "zero-weight item {i} chosen {} times",
            observed[i]
        );
    }
    let expected: Vec<f64> = pmf.iter().map(|p| p * SAMPLES as f64).collect();
    check(
        "Discrete1D indices",
        &chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED),
    );
}

#[test]
fn t16_discrete_rescaled_u() {
    // Joint test of (index, u rescaled) on cells (item, 20 bins of u): u rescaled must be
    // uniform in [0, 1) within every item, independently of which item was chosen.
    const U_BINS: usize = 20;
    let dist = Discrete1D::new(WEIGHTS).expect("valid weights");
    let pmf = reference_pmf();
    let mut rng = Pcg32::new(16);
    let mut observed = vec![0.0; WEIGHTS.len() * U_BINS];
    for _ in 0..SAMPLES {
        let (i, ur) = dist.sample_reuse(rng.next_f32());
        assert!((0.0..1.0).contains(&ur), "u rescaled = {ur}");
        let bin = ((f64::from(ur) * U_BINS as f64) as usize).min(U_BINS - 1);
        observed[i * U_BINS + bin] += 1.0;
    }
    let expected: Vec<f64> = (0..WEIGHTS.len() * U_BINS)
        .map(|cell| pmf[cell / U_BINS] * SAMPLES as f64 / U_BINS as f64)
        .collect();
    check(
        "Discrete1D rescaled u (joint with index)",
        &chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED),
    );
}

// ---------------------------------------------------------------------------------------------
// 5. Pixel filters
// ---------------------------------------------------------------------------------------------

#[test]
fn t17_box_filter() {
    let r = PlaneChi2::default().run(
        |u| Some(Filter::Box.sample(u) + Vec2::splat(0.5)),
        |_| 1.0,
        17,
    );
    check("box filter", &r);
}

/// Steps of the tabulated Gaussian profile over `|x| ∈ [0, 2]`.
const G_STEPS: usize = 31;
const G_RADIUS: f64 = 2.0;

/// The Gaussian filter's documented 1-D density (stddev 0.5, radius 2): 31 constant steps over
/// `|x| ∈ [0, 2]`, mirrored; step `i` covers `[x_i, x_i + 2/31]` with `x_i = 2 i / 31` and has
/// the value `max(0, exp(-x_i² / (2 · 0.25)) - exp(-4 / (2 · 0.25)))`; normalized over [-2, 2].
/// Returned as the table of the 31 normalized step densities.
fn gaussian_step_table() -> Vec<f64> {
    let h = G_RADIUS / G_STEPS as f64;
    let values: Vec<f64> = (0..G_STEPS)
        .map(|i| {
            let x0 = h * i as f64;
            ((-x0 * x0 / 0.5).exp() - (-G_RADIUS * G_RADIUS / 0.5).exp()).max(0.0)
        })
        .collect();
    let total = 2.0 * h * values.iter().sum::<f64>();
    values.iter().map(|v| v / total).collect()
}

/// Evaluates the step density of [`gaussian_step_table`] at `x`.
fn gaussian_step_density(table: &[f64], x: f64) -> f64 {
    let h = G_RADIUS / G_STEPS as f64;
    if x.abs() > G_RADIUS {
        return 0.0;
    }
    table[((x.abs() / h) as usize).min(G_STEPS - 1)]
}

#[test]
fn t18_gaussian_filter() {
    // [-2, 2]^2 mapped to [0, 1]^2 (density × 16), 62 × 62 cells: one cell per step.
    let filter = Filter::Gaussian(GaussianFilter::new(0.5));
    let table = gaussian_step_table();
    let r = PlaneChi2 {
        bins_x: 2 * G_STEPS,
        bins_y: 2 * G_STEPS,
        samples: SAMPLES,
    }
    .run(
        |u| {
            let s = filter.sample(u);
            Some((s + Vec2::splat(2.0)) / 4.0)
        },
        |p| {
            let (x, y) = (4.0 * f64::from(p.x) - 2.0, 4.0 * f64::from(p.y) - 2.0);
            16.0 * gaussian_step_density(&table, x) * gaussian_step_density(&table, y)
        },
        18,
    );
    check("Gaussian filter (stddev 0.5)", &r);
}

/// The tent filter's documented 1-D density for radius `r`: 31 constant steps over
/// `|x| ∈ [0, r]`, step `i` covering `[r i / 31, r (i + 1) / 31]` with the value `1 - i / 31`
/// (the tent at the step's start, as Mitsuba 3 tabulates it), mirrored, normalized over
/// [-r, r].
fn tent_step_density(r: f64, x: f64) -> f64 {
    let h = r / G_STEPS as f64;
    if x.abs() > r {
        return 0.0;
    }
    let total: f64 = 2.0
        * h
        * (0..G_STEPS)
            .map(|i| 1.0 - i as f64 / G_STEPS as f64)
            .sum::<f64>();
    let i = ((x.abs() / h) as usize).min(G_STEPS - 1);
    (1.0 - i as f64 / G_STEPS as f64) / total
}

/// Chi-square of the tent filter of radius `r` against the step density of radius `claimed`.
fn tent_chi2(r: f32, claimed: f64) -> Chi2Result {
    let filter = Filter::Tent(TentFilter::new(r));
    filter_chi2(&filter, f64::from(r), |x| tent_step_density(claimed, x), 19)
}

/// Chi-square of `filter`'s offsets over `[-r, r]^2` against the product density
/// `density(x) density(y)`, one cell per step of the tables.
fn filter_chi2(filter: &Filter, r: f64, density: impl Fn(f64) -> f64, seed: u64) -> Chi2Result {
    // [-r, r]^2 mapped to [0, 1]^2 (density × 4 r²), one cell per step.
    PlaneChi2 {
        bins_x: 2 * G_STEPS,
        bins_y: 2 * G_STEPS,
        samples: SAMPLES,
    }
    .run(
        |u| {
            let s = filter.sample(u).as_dvec2();
            Some(((s + DVec2::splat(r)) / (2.0 * r)).as_vec2())
        },
        |p| {
            let (x, y) = (
                (2.0 * f64::from(p.x) - 1.0) * r,
                (2.0 * f64::from(p.y) - 1.0) * r,
            );
            4.0 * r * r * density(x) * density(y)
        },
        seed,
    )
}

#[test]
fn t19_tent_filter() {
    check("tent filter (radius 1.25)", &tent_chi2(1.25, 1.25));
    // Control: the same samples against a tent 10% wider must be rejected.
    let wrong = tent_chi2(1.25, 1.375);
    assert!(!wrong.passes(alpha()), "a wrong radius passed: {wrong}");
}

/// A filter with negative lobes as its documented 1-D step table: the filter `f` at the start
/// of each of 31 steps over `|x| ∈ [0, r]` (as Mitsuba 3 tabulates it), mirrored. Evaluated in
/// f64, independently of the core.
struct SignedSteps {
    r: f64,
    values: Vec<f64>,
}

impl SignedSteps {
    fn new(r: f64, f: impl Fn(f64) -> f64) -> Self {
        let values = (0..G_STEPS)
            .map(|i| f(r * i as f64 / G_STEPS as f64))
            .collect();
        SignedSteps { r, values }
    }

    /// The 1-D density of the samples, `g(f(x))` normalized over [-r, r]: `g = abs` is what the
    /// sampler claims; `g = max(0, .)` (negative lobes never drawn) is a control.
    fn density(&self, g: impl Fn(f64) -> f64, x: f64) -> f64 {
        let h = self.r / G_STEPS as f64;
        if x.abs() > self.r {
            return 0.0;
        }
        let total: f64 = 2.0 * h * self.values.iter().map(|&v| g(v)).sum::<f64>();
        g(self.values[((x.abs() / h) as usize).min(G_STEPS - 1)]) / total
    }
}

/// Chi-square of `filter`'s offsets against the density `g(f(x)) g(f(y))` of `steps`.
fn signed_chi2(filter: &Filter, steps: &SignedSteps, g: fn(f64) -> f64, seed: u64) -> Chi2Result {
    filter_chi2(filter, steps.r, |x| steps.density(g, x), seed)
}

#[test]
fn t20_mitchell_filter() {
    let third = 1.0 / 3.0;
    let filter = Filter::Mitchell(MitchellFilter::new(third as f32, third as f32).unwrap());
    let steps = SignedSteps::new(2.0, |x| mitchell(third, third, x));
    check(
        "Mitchell filter (B = C = 1/3)",
        &signed_chi2(&filter, &steps, f64::abs, 20),
    );
    // Controls: the same filter with its negative lobes dropped, and Catmull-Rom, must be
    // rejected.
    let dropped = signed_chi2(&filter, &steps, |v| v.max(0.0), 20);
    assert!(
        !dropped.passes(alpha()),
        "negative lobes dropped passed: {dropped}"
    );
    let catmull = SignedSteps::new(2.0, |x| mitchell(0.0, 0.5, x));
    let wrong = signed_chi2(&filter, &catmull, f64::abs, 20);
    assert!(
        !wrong.passes(alpha()),
        "Catmull-Rom's density passed: {wrong}"
    );
}

#[test]
fn t21_lanczos_filter() {
    let filter = Filter::Lanczos(LanczosFilter::new(3).unwrap());
    let steps = SignedSteps::new(3.0, |x| lanczos(3.0, x));
    check(
        "Lanczos filter (3 lobes)",
        &signed_chi2(&filter, &steps, f64::abs, 21),
    );
    // Control: the same filter with its negative lobes dropped must be rejected.
    let dropped = signed_chi2(&filter, &steps, |v| v.max(0.0), 21);
    assert!(
        !dropped.passes(alpha()),
        "negative lobes dropped passed: {dropped}"
    );
}

/// A rectangle as the `rectangle` shape builds it (corners (-1,-1), (1,-1), (1,1), (-1,1),
/// triangles (0,1,2) and (2,3,0), texture coordinates), stretched, sheared a little into a
/// parallelogram, turned and moved: a mesh that light sampling maps the unit square onto.
fn parallelogram_mesh() -> Mesh {
    let m = glam::Mat3::from_cols(
        Vec3::new(0.9, 0.1, 0.2),
        Vec3::new(0.35, 0.6, -0.3),
        Vec3::new(0.1, -0.2, 0.8),
    );
    let shift = Vec3::new(0.4, 0.9, 1.3);
    let positions = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(x, y)| m * Vec3::new(x, y, 0.0) + shift)
        .collect();
    let uvs = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        .iter()
        .map(|&(u, v)| Vec2::new(u, v))
        .collect();
    Mesh::new(positions, Vec::new(), uvs, vec![[0, 1, 2], [2, 3, 0]])
}

/// Directions of light samples on a parallelogram mesh (one affine map, not a triangle chosen
/// by area) from a point in front of it, against the density of its two triangles cast in
/// f64: uniform by area, as the mesh's pdf says. Control: the same samples against a density
/// that gives the first triangle 60% of the samples must be rejected.
#[test]
fn t22_parallelogram_directions() {
    let mesh = parallelogram_mesh();
    assert!(
        mesh.parallelogram().is_some(),
        "not taken for a parallelogram"
    );
    let tris: Vec<[Vec3; 3]> = (0..2).map(|i| mesh.vertices(i)).collect();
    let r = MESH_REF;
    let casts = casts_from(r, &tris, &mesh);
    let area: Vec<f64> = tris.iter().map(tri_area64).collect();
    let shape = mesh_shape(mesh);
    let run = |share: [f64; 2]| {
        mesh_directions_chi2(
            &shape,
            r,
            |w| {
                // The solid-angle density of a point uniform on triangle k with probability
                // share[k]: share[k] / area[k] converted by distance and cosine.
                let d = w.as_dvec3();
                let mut pdf = 0.0;
                for (k, (tri, ng)) in casts.iter().enumerate() {
                    if let Some(q) = tri.hit(d) {
                        let cos = ng.as_dvec3().dot(q.unit()).abs();
                        pdf += share[k] / area[k] * q.length_squared() / cos;
                    }
                }
                pdf
            },
            22,
        )
    };
    let total = area[0] + area[1];
    check(
        "parallelogram directions",
        &run([area[0] / total, area[1] / total]),
    );
    let wrong = run([0.6, 0.4]);
    assert!(!wrong.passes(alpha()), "a 60/40 split passed: {wrong}");
}

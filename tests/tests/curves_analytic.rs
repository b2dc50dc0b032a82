//! Curve intersections against closed forms and a dense reference.
//!
//! - A straight `linearcurve` of constant radius is a cylinder between its end spheres: where the
//!   analytic open cylinder (`Cylinder`) is entered from outside on its side, the curve is hit
//!   at the same t (1e-5 relative) with the same normal (1e-4), and its v is the axial fraction.
//! - A `bsplinecurve` of collinear, evenly spaced points of constant radius is the cylinder from
//!   its second to its second-to-last point: the same comparison over its three segments.
//! - The B-spline root finder (golden-section search to 1e-10 in the curve parameter, see
//!   `core/src/geometry/curve_bspline.rs`) against a dense reference on a curved tube: the
//!   minimum over 100000 parameters per segment of the spheres' near roots, each local minimum
//!   refined by ternary search to 1e-13. Every hit agrees within 2e-7 relative in t (the
//!   returned t is f32; measured worst 4.0e-8 over 78 hits of 500 rays); a ray only one side
//!   hits must graze (`|n.d| < 0.02`).
//!
//! Controls: the same straight curves against a cylinder 1% thicker must disagree on most
//! rays, and the dense reference of a tube 0.1% thicker must be rejected at the tolerance.
use glam::{DVec3, DVec4};
use tessera_core::geometry::{Curve, CurveBasis, Cylinder};
use tessera_core::math::{Norm, Ray};
use tessera_lab::stats::Pcg32;

/// Uniform in `[lo, hi)`.
fn uniform(rng: &mut Pcg32, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * f64::from(rng.next_u32()) / 4_294_967_296.0
}

fn sphere_dir(rng: &mut Pcg32) -> DVec3 {
    let z = uniform(rng, -1.0, 1.0);
    let phi = uniform(rng, 0.0, std::f64::consts::TAU);
    let s = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// Rays from a sphere of radius 6 around the origin toward points of the box `[-h, h]^3`.
fn rays(n: usize, h: f64, seed: u64) -> Vec<Ray> {
    let mut rng = Pcg32::new(seed);
    (0..n)
        .map(|_| {
            let o = sphere_dir(&mut rng) * 6.0;
            let p = DVec3::new(
                uniform(&mut rng, -h, h),
                uniform(&mut rng, -h, h),
                uniform(&mut rng, -h, h),
            );
            Ray::new(o.as_vec3(), (p - o).unit().as_vec3())
        })
        .collect()
}

/// The cylinder around the segment from `a` to `b` of radius `r`.
fn cylinder(a: DVec3, b: DVec3, r: f64) -> Cylinder {
    let z = (b - a).unit();
    let x = z.any_orthonormal_vector();
    Cylinder {
        origin: a,
        axes: [x, z.cross(x), z],
        radius: r,
        length: (b - a).norm(),
    }
}

/// Compares the curve's hits with the cylinder's side entries: `(compared, mismatches)`.
fn against_cylinder(curve: &Curve, cyl: &Cylinder, rays: &[Ray]) -> (usize, Vec<String>) {
    let (mut compared, mut bad) = (0, Vec::new());
    for ray in rays {
        let Some(tc) = cyl.intersect(ray, f32::INFINITY) else {
            continue;
        };
        let (_, _, l) = cyl.project(ray.at(tc));
        let nc = cyl.normal(l.x, l.y);
        if nc.dot(ray.d) >= 0.0 {
            continue; // the cylinder's inside: the curve's caps are in the way
        }
        compared += 1;
        let hit = (0..curve.segment_count())
            .filter_map(|s| curve.intersect(s, ray, f32::INFINITY).map(|h| (s, h)))
            .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0));
        let Some((seg, (t, v))) = hit else {
            bad.push(format!("{ray:?}: missed, cylinder at {tc}"));
            continue;
        };
        let (_, _, surf) = curve.surface(seg, v, ray.at(t));
        let along = (seg as f64 + f64::from(v)) / curve.segment_count() as f64;
        let ok = (t - tc).abs() <= 1e-5 * tc
            && (surf.n - nc).abs().max_element() <= 1e-4
            && (along - l.z / cyl.length).abs() <= 1e-4;
        if !ok {
            bad.push(format!(
                "{ray:?}: t {t} n {} v {along}; cylinder t {tc} n {nc} v {}",
                surf.n,
                l.z / cyl.length
            ));
        }
    }
    (compared, bad)
}

fn straight_linear(a: DVec3, b: DVec3, r: f64) -> Curve {
    Curve {
        basis: CurveBasis::Linear,
        points: vec![a.extend(r), b.extend(r)],
        segments: vec![0],
        first: vec![true],
    }
}

/// Six collinear points evenly spaced from `a` by `step`: three segments spanning the points
/// from index 1 to 4.
fn straight_bspline(a: DVec3, step: DVec3, r: f64) -> Curve {
    Curve {
        basis: CurveBasis::BSpline,
        points: (0..6).map(|k| (a + step * k as f64).extend(r)).collect(),
        segments: vec![0, 1, 2],
        first: vec![true, false, false],
    }
}

#[test]
fn straight_curves_are_cylinders() {
    let (a, b, r) = (
        DVec3::new(-1.2, 0.3, -0.4),
        DVec3::new(1.0, -0.2, 0.6),
        0.35,
    );
    let rs = rays(4000, 1.2, 3);
    let lin = straight_linear(a, b, r);
    let (n, bad) = against_cylinder(&lin, &cylinder(a, b, r), &rs);
    println!(
        "linearcurve: {n} side hits compared, {} mismatches",
        bad.len()
    );
    assert!(
        n > 1000 && bad.is_empty(),
        "{n}: {:?}",
        &bad[..bad.len().min(5)]
    );

    let step = (b - a) / 3.0;
    let bs = straight_bspline(a - step, step, r);
    let (n, bad) = against_cylinder(&bs, &cylinder(a, b, r), &rs);
    println!(
        "bsplinecurve: {n} side hits compared, {} mismatches",
        bad.len()
    );
    assert!(
        n > 1000 && bad.is_empty(),
        "{n}: {:?}",
        &bad[..bad.len().min(5)]
    );
}

/// The control: a cylinder 1% thicker disagrees with both curves on most compared rays.
#[test]
fn straight_curves_control_thicker_cylinder_disagrees() {
    let (a, b, r) = (
        DVec3::new(-1.2, 0.3, -0.4),
        DVec3::new(1.0, -0.2, 0.6),
        0.35,
    );
    let rs = rays(4000, 1.2, 3);
    let step = (b - a) / 3.0;
    for curve in [
        straight_linear(a, b, r),
        straight_bspline(a - step, step, r),
    ] {
        let (n, bad) = against_cylinder(&curve, &cylinder(a, b, r * 1.01), &rs);
        println!("{:?}: {} of {n} disagree", curve.basis, bad.len());
        assert!(bad.len() * 2 > n, "{:?}: {} of {n}", curve.basis, bad.len());
    }
}

/// A curved B-spline tube of constant radius (two segments).
fn wave(r: f64) -> Curve {
    let p = [
        (-1.5, 0.0, -0.6),
        (-0.8, 0.9, 0.5),
        (0.0, -0.4, 0.9),
        (0.7, 0.5, -0.3),
        (1.4, -0.2, 0.4),
    ];
    Curve {
        basis: CurveBasis::BSpline,
        points: p.iter().map(|&(x, y, z)| DVec4::new(x, y, z, r)).collect(),
        segments: vec![0, 1],
        first: vec![true, false],
    }
}

/// The uniform cubic B-spline of segment `seg` of `c` at `v`: centre.
fn centre(c: &Curve, seg: usize, v: f64) -> DVec3 {
    let p: Vec<DVec3> = (0..4)
        .map(|k| c.points[c.segments[seg] as usize + k].truncate())
        .collect();
    let w = 1.0 - v;
    (p[0] * (w * w * w)
        + p[1] * (3.0 * v * v * v - 6.0 * v * v + 4.0)
        + p[2] * (-3.0 * v * v * v + 3.0 * v * v + 3.0 * v + 1.0)
        + p[3] * (v * v * v))
        / 6.0
}

/// The dense reference: the smallest interior minimum of the spheres' near roots over the
/// whole curve (radius `r`; its segments joined, as one curve), in front of the origin and met
/// from outside: `(t, normal)`. Each local minimum of the samples is refined by ternary search
/// to 1e-13 in the curve parameter.
fn dense(c: &Curve, r: f64, o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
    const N: usize = 100_000;
    let segs = c.segment_count();
    let at = |g: f64| {
        let seg = (g.floor() as usize).min(segs - 1);
        centre(c, seg, g - seg as f64)
    };
    let near = |g: f64| {
        let w = at(g) - o;
        let b = w.dot(d);
        let q = w.length_squared() - b * b;
        (q <= r * r).then(|| b - (r * r - q).sqrt())
    };
    let total = N * segs;
    let g_of = |k: usize| k as f64 / N as f64;
    let ts: Vec<Option<f64>> = (0..=total).map(|k| near(g_of(k))).collect();
    let mut best: Option<(f64, DVec3)> = None;
    for k in 1..total {
        let (Some(l), Some(m), Some(h)) = (ts[k - 1], ts[k], ts[k + 1]) else {
            continue;
        };
        if !(m <= l && m <= h) {
            continue;
        }
        let (mut lo, mut hi) = (g_of(k - 1), g_of(k + 1));
        let f = |g: f64| near(g).unwrap_or(f64::INFINITY);
        while hi - lo > 1e-13 {
            let (a, b) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if f(a) <= f(b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        let g = 0.5 * (lo + hi);
        let t = f(g).min(m);
        let n = (o + d * t - at(g)).unit();
        if t > 0.0 && n.dot(d) < 0.0 && best.is_none_or(|(bt, _)| t < bt) {
            best = Some((t, n));
        }
    }
    best
}

/// Our hits against the dense reference of radius `r_ref`: `(hits compared, worst relative t
/// error, rays hit by one side only that do not graze)`.
fn against_dense(r_ref: f64) -> (usize, f64, usize) {
    let curve = wave(0.2);
    let (mut n, mut worst, mut lone) = (0, 0.0f64, 0);
    for ray in rays(500, 1.0, 11) {
        let ours = (0..curve.segment_count())
            .filter_map(|s| curve.intersect(s, &ray, f32::INFINITY).map(|h| (s, h)))
            .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0));
        // The reference walks a unit direction; t is along the ray's own (f32) direction.
        let len = ray.d.as_dvec3().norm();
        let theirs = dense(&curve, r_ref, ray.o.as_dvec3(), ray.d.as_dvec3() / len)
            .map(|(t, n)| (t / len, n));
        match (ours, theirs) {
            (Some((_, (t, _))), Some((tr, _))) => {
                n += 1;
                worst = worst.max((f64::from(t) - tr).abs() / tr);
            }
            (Some((s, (t, v))), None) => {
                let (_, _, surf) = curve.surface(s, v, ray.at(t));
                lone += (surf.n.dot(ray.d).abs() >= 0.02) as usize;
            }
            (None, Some((_, nr))) => lone += (nr.as_vec3().dot(ray.d).abs() >= 0.02) as usize,
            (None, None) => {}
        }
    }
    (n, worst, lone)
}

#[test]
fn bspline_root_finder_matches_a_dense_reference() {
    let (n, worst, lone) = against_dense(0.2);
    println!("{n} hits, worst relative t error {worst:e}, {lone} non-grazing lone hits");
    assert!(n > 60 && worst <= 2e-7 && lone == 0, "{n} {worst} {lone}");
}

/// The control: the dense reference of a tube 0.1% thicker is rejected at the tolerance.
#[test]
fn bspline_root_finder_control_thicker_reference_disagrees() {
    let (n, worst, _) = against_dense(0.2 * 1.001);
    println!("{n} hits, worst relative t error {worst:e}");
    assert!(worst > 2e-7, "{worst}");
}

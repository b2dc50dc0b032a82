//! Chi-square test of the cylinder's light sampling (`Shape::sample_toward`, the density it
//! returns, as `tests/tests/emitters_chi2.rs` tests other samplers), from reference points
//! outside, inside and on the axis's extension of a tilted cylinder far from the origin.
//!
//! Each sampled point is mapped, in f64 and with a frame built here (not the core's), to the
//! square (angle around the axis / 2 pi, height / length); the claimed density there is the
//! returned solid-angle density times `|cos| / dist^2` times the lateral area `2 pi r l`, which
//! must be a density of the square (integral 1). Control: the same samples against the density
//! of a cylinder whose radius is 2% larger must fail.
use glam::{DVec3, Vec2};
use tessera_core::geometry::{Cylinder, Shape, ShapeKind};
use tessera_core::math::Norm;
use tessera_lab::stats::{sidak_alpha, PlaneChi2};

const N_TESTS: usize = 3;

fn cylinder(origin: DVec3, axis: DVec3, radius: f64, length: f64) -> Shape {
    let z = axis.unit();
    let x = z.any_orthonormal_vector();
    let y = z.cross(x);
    Shape {
        kind: ShapeKind::Cylinder(Cylinder {
            origin,
            axes: [x, y, z],
            radius,
            length,
        }),
        bsdf: 0,
        emitter: None,
        flip_normals: false,
    }
}

/// (angle / 2 pi, height / length) of `p`, in a frame of the test's own.
fn square(p: DVec3, origin: DVec3, axis: DVec3, length: f64) -> (Vec2, DVec3) {
    let z = axis.unit();
    let x = if z.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let x = (x - z * z.dot(x)).unit();
    let y = z.cross(x);
    let v = p - origin;
    let h = v.dot(z);
    let mut phi = v.dot(y).atan2(v.dot(x));
    if phi < 0.0 {
        phi += std::f64::consts::TAU;
    }
    let n = (v - z * h).unit();
    // The point is rounded to f32 2000 from the origin (steps of 1e-4): its height may fall
    // that far outside the cylinder's ends.
    (
        Vec2::new(
            (phi / std::f64::consts::TAU) as f32,
            (h / length).clamp(0.0, 1.0) as f32,
        ),
        n,
    )
}

/// The test from `r`; `claimed_radius` is the radius the density is converted with.
fn run(r: DVec3, claimed_radius: f64, seed: u64) -> tessera_lab::stats::Chi2Result {
    let origin = DVec3::new(1000.0, -2000.0, 500.0);
    let axis = DVec3::new(0.3, 1.0, -0.4);
    let (radius, length) = (0.7, 2.5);
    let shape = cylinder(origin, axis, radius, length);
    let rf = (origin + r).as_vec3();
    let area = std::f64::consts::TAU * claimed_radius * length;
    PlaneChi2 {
        bins_x: 16,
        bins_y: 8,
        samples: 1_000_000,
    }
    .run(
        |u| {
            let s = shape.sample_toward(rf, u, &[], true)?;
            let p = s.ps.p.as_dvec3();
            let (q, _) = square(p, origin, axis, length);
            Some(q)
        },
        |q| {
            // The density of the square at q, by the shape's own pdf_from.
            let z = axis.unit();
            let x = if z.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
            let x = (x - z * z.dot(x)).unit();
            let y = z.cross(x);
            let phi = f64::from(q.x) * std::f64::consts::TAU;
            let n = x * phi.cos() + y * phi.sin();
            let p = origin + n * radius + z * (f64::from(q.y) * length);
            let d = p - rf.as_dvec3();
            let dist2 = d.length_squared();
            let cos = n.dot(d).abs() / dist2.sqrt();
            let pdf = shape.pdf_from(rf, p.as_vec3(), n.as_vec3(), &[]);
            f64::from(pdf) * cos / dist2 * area
        },
        seed,
    )
}

#[test]
fn cylinder_light_sampling_matches_its_density() {
    let alpha = sidak_alpha(0.01, N_TESTS);
    let cases = [
        ("outside", DVec3::new(2.0, 0.5, 1.5)),
        ("inside", DVec3::new(0.1, 1.0, -0.2)),
        ("beyond an end", DVec3::new(-0.6, -2.0, 0.8)),
    ];
    for (k, (name, r)) in cases.iter().enumerate() {
        let res = run(*r, 0.7, k as u64);
        println!("{name}: {res}");
        assert!(res.passes(alpha), "{name}: {res} (alpha {alpha:.3e})");
    }
    let res = run(cases[0].1, 0.7 * 1.02, 0);
    println!("control (radius claimed 2% larger): {res}");
    assert!(!res.passes(alpha), "control passed: {res}");
}

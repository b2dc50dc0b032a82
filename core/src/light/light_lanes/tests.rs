//! Tests of the lanes: the light-by-light loop's bits on random vertices, and where the lanes
//! step aside.
use super::*;
use crate::bsdf::{Diffuse, RoughConductor};
use crate::geometry::Interaction;
use crate::light::VertexSelection;
use crate::sampling::owen::mix64;
use crate::sampling::warp::square_to_uniform_sphere;
use crate::texture::Texture;
use crate::Color;
use glam::Vec2;

fn unit(h: u64) -> f32 {
    (h >> 40) as f32 / (1u64 << 24) as f32
}

/// Case `r`'s `k`-th uniform number.
fn u(r: u64, k: u64) -> f32 {
    unit(mix64(r ^ k.wrapping_mul(0x9e37_79b9_7f4a_7c15)))
}

fn bsdfs() -> [Bsdf; 5] {
    let conductor = |kind, alpha_u: f32, alpha_v: f32| {
        let mut distribution = Microfacet::new(kind, alpha_u);
        distribution.alpha_v = alpha_v;
        Bsdf::RoughConductor(RoughConductor {
            distribution,
            roughness: None,
            eta: Texture::Constant(Color::ZERO),
            k: Texture::Constant(Color::ONE),
            specular_reflectance: Texture::Constant(Color::ONE),
        })
    };
    [
        Bsdf::Diffuse(Diffuse {
            reflectance: Texture::Constant(Color::splat(0.5)),
        }),
        conductor(MicrofacetKind::Ggx, 0.05, 0.05),
        conductor(MicrofacetKind::Ggx, 0.3, 0.08),
        conductor(MicrofacetKind::Beckmann, 0.01, 0.01),
        conductor(MicrofacetKind::Beckmann, 0.4, 0.2),
    ]
}

/// Random cases: 2 to 8 lights of every kind (mostly with a position), of sizes, distances
/// and orientations over several decades, a vertex with a random frame and incident
/// direction (below the surface too).
fn case(r: u64) -> (alloc::vec::Vec<LightBound>, Interaction, Vec3) {
    let n = 2 + (u(r, 0) * 7.0) as usize;
    let bounds = (0..n as u64)
        .map(|k| {
            let at = Vec3::new(u(r, 10 + k), u(r, 20 + k), u(r, 30 + k)) * 20.0 - Vec3::splat(10.0);
            let size = 10f32.powf(u(r, 40 + k) * 3.0 - 2.5);
            let lum = 10f32.powf(u(r, 50 + k) * 4.0 - 2.0);
            let dir = square_to_uniform_sphere(Vec2::new(u(r, 60 + k), u(r, 70 + k)));
            match (u(r, 80 + k) * 12.0) as u32 {
                0..=3 => LightBound::Sphere {
                    center: at,
                    radius: size,
                    lum,
                },
                4..=6 => LightBound::Flat {
                    center: at,
                    normal: dir,
                    area: size * size * 40.0,
                    lum,
                },
                7 | 8 => LightBound::Solid {
                    center: at,
                    area: size * size * 40.0,
                    lum,
                },
                9 => LightBound::Point { position: at, lum },
                10 => LightBound::Direction { to_light: dir, lum },
                _ => LightBound::Environment { lum },
            }
        })
        .collect();
    let n = square_to_uniform_sphere(Vec2::new(u(r, 1), u(r, 2)));
    let si = Interaction {
        p: Vec3::new(u(r, 3), u(r, 4), u(r, 5)) * 4.0 - Vec3::splat(2.0),
        p_err: Vec3::ZERO,
        t: 1.0,
        ng: n,
        frame: Frame::from_normal(n),
        uv: Vec2::ZERO,
        shape: 0,
        wi: n,
    };
    let wi = square_to_uniform_sphere(Vec2::new(u(r, 6), u(r, 7)));
    (bounds, si, wi)
}

fn bits(s: &VertexSelection, n: usize) -> alloc::vec::Vec<u32> {
    (0..n).map(|k| s.pdf(k).to_bits()).collect()
}

/// Four lights to a vector give the light-by-light probabilities bit for bit, for every
/// kind of light and every BSDF the lanes weigh. Control: the same comparison with the vertex moved by 1e-3 finds
/// different bits, so it can fail.
#[test]
fn lanes_give_the_light_by_light_bits() {
    let (mut compared, mut moved_differs) = (0, 0);
    for r in 0..6000u64 {
        let (bounds, si, wi) = case(r);
        let Some(lanes) = LightLanes::of(&bounds) else {
            continue;
        };
        for bsdf in &bsdfs() {
            let at = Vec2::ZERO.into();
            let one = VertexSelection::new(&bounds, None, &si, bsdf, &at, wi).unwrap();
            let four = VertexSelection::new(&bounds, Some(&lanes), &si, bsdf, &at, wi).unwrap();
            if lanes.weights(si.p, &si.frame, bsdf, wi, |_| None).is_none() {
                continue;
            }
            assert_eq!(
                bits(&one, bounds.len()),
                bits(&four, bounds.len()),
                "case {r}"
            );
            compared += 1;
            let moved = Interaction {
                p: si.p + Vec3::X * 1e-3,
                ..si
            };
            let other = VertexSelection::new(&bounds, None, &moved, bsdf, &at, wi).unwrap();
            moved_differs += usize::from(bits(&other, bounds.len()) != bits(&four, bounds.len()));
        }
    }
    assert!(compared > 10_000, "only {compared} cases compared");
    // About a quarter differ: in most cases every light weighs zero (the incident direction
    // below the surface, a lobe facing away) and the choice is even wherever the vertex is.
    assert!(
        moved_differs > compared / 10,
        "control: {moved_differs} of {compared}"
    );
}

/// Lanes exist only for 2 to 8 lights, at least two with a position; a vertex inside a
/// light, or a BSDF the lanes do not weigh, leaves the weighing to the light-by-light loop.
#[test]
fn lanes_step_aside_where_they_do_not_apply() {
    let sphere = |x: f32| LightBound::Sphere {
        center: Vec3::new(x, 0.0, 0.0),
        radius: 1.0,
        lum: 1.0,
    };
    let sky = LightBound::Environment { lum: 1.0 };
    assert!(LightLanes::of(&[sphere(0.0)]).is_none());
    assert!(LightLanes::of(&[sphere(0.0); LANE_LIGHTS + 1]).is_none());
    assert!(LightLanes::of(&[sphere(0.0), sky]).is_none());
    assert!(LightLanes::of(&[sphere(0.0), sky, sphere(3.0)]).is_some());
    let point = LightBound::Point {
        position: Vec3::ZERO,
        lum: 1.0,
    };
    let lanes = LightLanes::of(&[sphere(5.0), sphere(-5.0), point]).unwrap();
    let f = Frame::from_normal(Vec3::Z);
    let diffuse = &bsdfs()[0];
    let none = |_| None;
    assert!(lanes
        .weights(Vec3::Y * 3.0, &f, diffuse, Vec3::Z, none)
        .is_some());
    assert!(lanes
        .weights(Vec3::X * 4.5, &f, diffuse, Vec3::Z, none)
        .is_none());
    assert!(lanes
        .weights(Vec3::ZERO, &f, diffuse, Vec3::Z, none)
        .is_none());
    let mirror = Bsdf::Mirror(crate::bsdf::Mirror {});
    assert!(lanes
        .weights(Vec3::Y * 3.0, &f, &mirror, Vec3::Z, none)
        .is_none());
}

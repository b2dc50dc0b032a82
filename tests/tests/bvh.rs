//! The BVH finds exactly what a brute-force loop over every primitive finds: closest hits
//! (distance and primitive) and occlusion, on random triangle soups with spheres and disks.
use tessera_core::bsdf::{Bsdf, Diffuse};
use tessera_core::camera::{Camera, Filter, FovAxis};
use tessera_core::geometry::{Disk, Mesh, Shape, ShapeKind, Sphere};
use tessera_core::glam::{Mat4, Vec2, Vec3};
use tessera_core::math::{Norm, Ray, Transform};
use tessera_core::scene::{Scene, SceneParts};
use tessera_core::texture::Texture;

use tessera_tests::rng::SplitMix as Rng;
use tessera_tests::soup::brute_closest;

fn random_scene(rng: &mut Rng, triangles: usize) -> Scene {
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for t in 0..triangles {
        let c = rng.v(20.0);
        for _ in 0..3 {
            positions.push(c + rng.v(if t % 10 == 0 { 8.0 } else { 1.5 }));
        }
        let b = (3 * t) as u32;
        indices.push([b, b + 1, b + 2]);
    }
    let mut shapes = vec![Shape {
        kind: ShapeKind::Mesh(Mesh::new(positions, vec![], vec![], indices)),
        bsdf: 0,
        emitter: None,
        flip_normals: false,
    }];
    for _ in 0..20 {
        shapes.push(Shape {
            kind: ShapeKind::Sphere(Sphere {
                center: rng.v(20.0),
                radius: 0.2 + rng.f(),
            }),
            bsdf: 0,
            emitter: None,
            flip_normals: false,
        });
    }
    let mut disks = Vec::new();
    for i in 0..5 {
        let m = Mat4::from_translation(rng.v(20.0))
            * Mat4::from_rotation_x(rng.f() * 3.0)
            * Mat4::from_scale(Vec3::new(1.0 + rng.f(), 0.5, 1.0));
        disks.push(Disk::new(Transform::new(m).unwrap()).unwrap());
        shapes.push(Shape {
            kind: ShapeKind::Disk(i),
            bsdf: 0,
            emitter: None,
            flip_normals: false,
        });
    }
    let camera = Camera::perspective(Transform::IDENTITY, 4, 4, 40.0, FovAxis::X, 0.01, 1e4);
    let parts = SceneParts {
        shapes,
        disks,
        bsdfs: vec![Bsdf::Diffuse(Diffuse {
            reflectance: Texture::constant(0.5),
        })],
        emitters: vec![],
        camera,
        filter: Filter::Box,
        light_selection: Default::default(),
        groups: Vec::new(),
        instances: Vec::new(),
    };
    Scene::new(parts).expect("valid scene")
}

#[test]
fn bvh_agrees_with_brute_force() {
    let mut rng = Rng(42);
    for triangles in [1usize, 7, 100, 3000] {
        let scene = random_scene(&mut rng, triangles);
        let mut hits = 0;
        for _ in 0..4000 {
            let o = rng.v(50.0);
            let target = rng.v(20.0);
            let mut ray = Ray::new(o, (target - o).unit());
            if rng.f() < 0.3 {
                ray.t_max = rng.f() * 40.0;
            }
            let best = brute_closest(&scene, &ray);
            let hit = scene.intersect_hit(&ray);
            match (best, hit) {
                (None, None) => {}
                (Some((t, i)), Some(h)) => {
                    hits += 1;
                    assert_eq!(t, h.t, "closest distance differs");
                    assert_eq!(i as u32, h.prim, "closest primitive differs");
                }
                (b, h) => panic!("brute force {b:?} vs BVH {h:?} ({triangles} triangles)"),
            }
            assert_eq!(scene.occluded(&ray), best.is_some(), "occlusion differs");
        }
        assert!(
            hits > 100,
            "too few hits ({hits}) for the test to mean anything"
        );
    }
    let _ = Vec2::ZERO;
}

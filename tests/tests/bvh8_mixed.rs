//! The 8-wide BVH on soups of spheres and disks mixed with triangles: leaves whose blocks hold
//! no triangle (the triangle test is skipped), some, or only triangles, and one-node hierarchies
//! (the stackless walk of `accel/root.rs`). Closest and any hits agree with brute force and the
//! other walks (`tessera_tests::wide::compare`). Control: leaves blind to spheres and disks must
//! disagree.
use tessera_core::accel::tri_block::Ray4;
use tessera_core::accel::{AnyLeaves, Bvh8, ClosestLeaves};
use tessera_core::geometry::{Disk, Hit, Mesh, ShapeKind, Sphere, TriRay};
use tessera_core::glam::{EulerRot, Mat4, Quat, Vec3};
use tessera_core::math::Transform;
use tessera_core::scene::Scene;
use tessera_tests::rng::SplitMix as Rng;
use tessera_tests::soup::{diffuse_shape, random_rays, random_soup, scene_of};
use tessera_tests::wide::{compare, WideScene};

/// A scene of a triangle soup (one mesh), spheres and disks (random ellipses), all diffuse.
fn mixed_scene(rng: &mut Rng, tris: usize, spheres: usize, disks: usize) -> Scene {
    let corners = random_soup(rng, tris);
    let positions: Vec<Vec3> = corners.iter().flatten().copied().collect();
    let indices: Vec<[u32; 3]> = (0..tris as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    let (mut shapes, mut disk_list) = (Vec::new(), Vec::new());
    if tris > 0 {
        let mesh = Mesh::new(positions, vec![], vec![], indices);
        shapes.push(diffuse_shape(ShapeKind::Mesh(mesh)));
    }
    for _ in 0..spheres {
        let sphere = Sphere {
            center: rng.v(20.0),
            radius: 0.2 + 1.5 * rng.f(),
        };
        shapes.push(diffuse_shape(ShapeKind::Sphere(sphere)));
    }
    for _ in 0..disks {
        let m = Mat4::from_scale_rotation_translation(
            Vec3::new(0.3 + 2.0 * rng.f(), 0.3 + 2.0 * rng.f(), 1.0),
            Quat::from_euler(EulerRot::XYZ, 6.0 * rng.f(), 6.0 * rng.f(), 6.0 * rng.f()),
            rng.v(20.0),
        );
        let disk = Disk::new(Transform::new(m).expect("invertible")).expect("a disk");
        shapes.push(diffuse_shape(ShapeKind::Disk(disk_list.len() as u32)));
        disk_list.push(disk);
    }
    scene_of(shapes, disk_list)
}

/// Leaves of spheres and disks alone (blocks, and pairs of blocks, without a triangle: the
/// triangle test is skipped), and mixed with triangles (those lanes go straight to the
/// primitive's own test): closest hits and any hits equal brute force's, the greedily collapsed
/// and portable walks' and the scene's own casts'. Control: leaves whose test of the primitives that
/// are not triangles always misses must disagree with brute force.
#[test]
fn agrees_on_soups_of_spheres_and_disks() {
    let mut rng = Rng(29);
    let mut hits = 0;
    let mut kinds = [0usize; 3];
    let mut one_node = 0;
    for (tris, spheres, disks) in [
        (0, 1, 0),
        (0, 0, 1),
        (0, 9, 0),
        (0, 0, 9),
        (0, 30, 30),
        (3, 20, 10),
        (40, 40, 40),
        (0, 400, 0),
        (600, 80, 80),
    ] {
        let s = mixed_scene(&mut rng, tris, spheres, disks);
        // Which kinds of blocks the leaves hold: no triangle, some, only triangles.
        for node in &s.bvh.nodes {
            for lane in (0..8).filter(|&l| node.leaves & (1 << l) != 0) {
                let (first, count) = (node.child[lane] as usize, usize::from(node.count[lane]));
                for k in 0..count.div_ceil(4) {
                    let b = &s.blocks.blocks[first + k];
                    let used = (count - 4 * k).min(4);
                    let nan = (0..used).filter(|&l| b.v[0][l].is_nan()).count();
                    kinds[if nan == used {
                        0
                    } else if nan > 0 {
                        1
                    } else {
                        2
                    }] += 1;
                }
            }
        }
        // One-node hierarchies take the stackless walk (accel/root.rs).
        one_node += usize::from(s.bvh.nodes.len() == 1);
        let w8 = WideScene::<Bvh8>::new(&s);
        let rays = random_rays(&mut rng, 1500);
        let (h, bad) = compare(&s, &w8, &rays);
        assert_eq!(bad, 0, "{tris}/{spheres}/{disks}: {bad} rays disagree");
        hits += h;
    }
    eprintln!("{hits} hits; blocks without, with some, with only triangles: {kinds:?}");
    assert!(hits > 3000, "too few hits ({hits}) to mean anything");
    assert!(kinds.iter().all(|&k| k > 3), "block kinds {kinds:?}");
    assert!(
        (3..9).contains(&one_node),
        "{one_node} one-node hierarchies"
    );

    // Control: spheres and disks never hit.
    let s = mixed_scene(&mut rng, 40, 60, 60);
    let mut bad = 0;
    for ray in random_rays(&mut rng, 1500) {
        let tri = TriRay::new(&ray);
        let r4 = Ray4::new(&tri);
        let mut best = None;
        let blind = |_: usize, _: &[Vec3; 3], _: f32| None;
        s.bvh.cast::<false>(
            &ray,
            ClosestLeaves {
                blocks: &s.blocks,
                ray: &r4,
                best: &mut best,
                other: blind,
            },
        );
        let mut any = AnyLeaves {
            blocks: &s.blocks,
            ray: &r4,
            hit: false,
            other: blind,
        };
        s.bvh.cast::<true>(&ray, &mut any);
        let h = s.intersect_hit(&ray);
        if best.map(|b: Hit| b.t.to_bits()) != h.map(|h| h.t.to_bits()) || any.hit != h.is_some() {
            bad += 1;
        }
    }
    eprintln!("control: {bad} of 1500 rays disagree");
    assert!(
        bad > 100,
        "blind leaves went unnoticed ({bad} rays disagree)"
    );
}

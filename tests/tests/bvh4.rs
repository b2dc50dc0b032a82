//! The 4-wide BVH and its SIMD box test: exact agreement with brute force (closest distance and
//! primitive, occlusion) on triangle soups with degenerate triangles, axis-parallel rays and
//! rays starting on box planes; the SSE and the portable slab tests give the same bits; the
//! portable one is conservative against an independent f64 check; structure invariants.
use tessera_core::accel::simd::{hit4_scalar, Boxes4, RayPre, MAX_X, MIN_X};
use tessera_core::accel::Bvh4;
use tessera_core::geometry::{Sphere, TriRay};
use tessera_core::glam::Vec3;
use tessera_core::math::{Aabb, Ray};
use tessera_core::scene::Scene;

use tessera_tests::rng::SplitMix as Rng;
use tessera_tests::soup::{brute_closest, random_rays, random_soup, scene};

/// Checks the scene against a loop over every primitive; returns the number of hits. Exact ties
/// may resolve to either primitive; there must be few of them.
fn check_rays(scene: &Scene, rays: &[Ray]) -> usize {
    let (mut hits, mut ties) = (0, 0);
    for ray in rays {
        let best = brute_closest(scene, ray);
        let hit = scene.intersect_hit(ray);
        match (best, hit) {
            (None, None) => {}
            (Some((t, i)), Some(h)) => {
                hits += 1;
                assert!(
                    h.t.is_finite() && h.t > 0.0,
                    "bad distance {} for {ray:?}",
                    h.t
                );
                assert_eq!(t, h.t, "closest distance differs for {ray:?}");
                if i as u32 != h.prim {
                    // An exact tie (a ray along an edge shared by two triangles): the other
                    // primitive must be hit at the very same distance.
                    let tri = TriRay::new(ray);
                    let other = scene.intersect_prim(h.prim as usize, ray, &tri, ray.t_max);
                    assert_eq!(other.map(|o| o.0), Some(t), "closest primitive differs");
                    ties += 1;
                }
            }
            (b, h) => panic!("brute force {b:?} vs BVH4 {h:?} for {ray:?}"),
        }
        assert_eq!(scene.occluded(ray), best.is_some(), "any hit differs");
    }
    assert!(ties * 20 <= hits, "{ties} ties in {hits} hits");
    hits
}

#[test]
fn wide_bvh_agrees_with_brute_force_on_soups() {
    let mut rng = Rng(7);
    let mut hits = 0;
    for n in [1usize, 2, 3, 4, 5, 9, 64, 500, 5000] {
        let spheres = (0..n % 4)
            .map(|_| Sphere {
                center: rng.v(20.0),
                radius: 0.3 + rng.f(),
            })
            .collect();
        let s = scene(random_soup(&mut rng, n), spheres);
        let rays = random_rays(&mut rng, 3000);
        hits += check_rays(&s, &rays);
    }
    assert!(hits > 3000, "too few hits ({hits}) to mean anything");
}

#[test]
fn empty_scene_and_single_primitive() {
    let mut rng = Rng(3);
    let empty = scene(vec![], vec![]);
    assert!(empty.bvh.nodes.is_empty());
    assert!(empty.bounds().is_empty());
    for ray in random_rays(&mut rng, 100) {
        assert!(empty.intersect_hit(&ray).is_none());
        assert!(!empty.occluded(&ray));
    }
    let tri = [
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let one = scene(vec![tri], vec![]);
    assert_eq!(one.bvh.nodes.len(), 1);
    let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.0, -1.0));
    let h = one.intersect_hit(&ray).expect("hits the triangle");
    assert_eq!((h.t, h.prim), (5.0, 0));
    let mut short = ray;
    short.t_max = 4.0;
    assert!(one.intersect_hit(&short).is_none() && !one.occluded(&short));
    let sphere = scene(
        vec![],
        vec![Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        }],
    );
    assert!(sphere.occluded(&ray));
    let rays = random_rays(&mut rng, 500);
    check_rays(&one, &rays);
    check_rays(&sphere, &rays);
}

/// Axis-aligned quads on an integer grid, rays along the axes (zero direction components, also
/// negative zeros) starting on grid planes: slab distances `0 * inf` are NaN and must not cull.
#[test]
fn axis_parallel_rays_on_box_planes() {
    let mut tris = Vec::new();
    for i in 0..6 {
        for j in 0..6 {
            let (x, y, z) = (i as f32, j as f32, ((i * 7 + j * 3) % 5) as f32);
            // A unit quad in each axis plane, two triangles each.
            let quads = [
                [Vec3::new(x, y, z), Vec3::X, Vec3::Y],
                [Vec3::new(x, z, y), Vec3::X, Vec3::Z],
                [Vec3::new(z, x, y), Vec3::Y, Vec3::Z],
            ];
            for [p, u, v] in quads {
                tris.push([p, p + u, p + v]);
                tris.push([p + u, p + u + v, p + v]);
            }
        }
    }
    let s = scene(tris, vec![]);
    let mut rng = Rng(11);
    let dirs = [
        Vec3::X,
        -Vec3::X,
        Vec3::Y,
        -Vec3::Y,
        Vec3::Z,
        -Vec3::Z,
        Vec3::new(-0.0, -0.0, 1.0),
        Vec3::new(1.0, -0.0, 0.0),
        Vec3::new(0.0, -1.0, -0.0),
    ];
    let mut rays = Vec::new();
    for _ in 0..3000 {
        // Origins on grid planes (integers and halves) or anywhere.
        let mut c = || match rng.below_scaled(3) {
            0 => rng.below_scaled(8) as f32 - 1.0,
            1 => rng.below_scaled(16) as f32 * 0.5 - 1.0,
            _ => rng.f() * 8.0 - 1.0,
        };
        let o = Vec3::new(c(), c(), c());
        rays.push(Ray::new(o, dirs[rng.below_scaled(dirs.len())]));
    }
    let hits = check_rays(&s, &rays);
    assert!(hits > 300, "too few hits ({hits})");
}

fn random_boxes(rng: &mut Rng) -> Boxes4 {
    let mut b = Boxes4::EMPTY;
    for lane in 0..rng.below_scaled(5) {
        for a in 0..3 {
            let (p, q) = match rng.below_scaled(4) {
                // Flat boxes and boxes with a plane through typical origins.
                0 => (0.0, rng.f()),
                1 => {
                    let p = rng.f() - 0.5;
                    (p, p)
                }
                _ => (rng.f() * 4.0 - 2.0, rng.f() * 4.0 - 2.0),
            };
            b.b[MIN_X + a][lane] = p.min(q);
            b.b[MAX_X + a][lane] = p.max(q);
        }
    }
    b
}

fn random_box_ray(rng: &mut Rng) -> Ray {
    let mut c = |zero: bool| match rng.below_scaled(if zero { 5 } else { 3 }) {
        0 => 0.0,
        1 => -0.0,
        2 => rng.f() - 0.5,
        _ => rng.f() * 6.0 - 3.0,
    };
    let o = Vec3::new(c(false), c(false), c(false));
    let d = Vec3::new(c(true), c(true), c(true));
    let d = if d == Vec3::ZERO { Vec3::X } else { d };
    let mut ray = Ray::new(o, d);
    if rng.below_scaled(3) == 0 {
        ray.t_max = rng.f() * 3.0;
    }
    ray
}

#[test]
#[cfg(target_arch = "x86_64")]
fn sse_and_scalar_slab_tests_give_the_same_bits() {
    use tessera_core::accel::simd::hit4_sse;
    let mut rng = Rng(5);
    let mut hits = 0;
    for _ in 0..200_000 {
        let boxes = random_boxes(&mut rng);
        let ray = random_box_ray(&mut rng);
        let pre = RayPre::new(&ray);
        let (ms, ts) = hit4_sse(&boxes, &pre, ray.t_max);
        let (mp, tp) = hit4_scalar(&boxes, &pre, ray.t_max);
        assert_eq!(ms, mp, "masks differ for {ray:?} {boxes:?}");
        for lane in 0..4 {
            assert_eq!(ts[lane].to_bits(), tp[lane].to_bits(), "t_near differs");
            assert!(!ts[lane].is_nan());
        }
        hits += ms.count_ones();
    }
    assert!(hits > 10_000, "too few hits ({hits})");
}

/// The portable slab test never misses a box the ray passes through (checked in f64 by points
/// along the ray strictly inside the box), and rejects boxes the ray clearly misses.
#[test]
fn scalar_slab_test_is_conservative_and_rejects_misses() {
    let mut rng = Rng(9);
    let (mut inside, mut rejected) = (0, 0);
    for _ in 0..100_000 {
        let boxes = random_boxes(&mut rng);
        let ray = random_box_ray(&mut rng);
        let (mask, t_near) = hit4_scalar(&boxes, &RayPre::new(&ray), ray.t_max);
        for lane in 0..4 {
            let b = &boxes.b;
            let lo = [b[MIN_X][lane], b[MIN_X + 1][lane], b[MIN_X + 2][lane]];
            let hi = [b[MAX_X][lane], b[MAX_X + 1][lane], b[MAX_X + 2][lane]];
            let t_end = f64::from(ray.t_max.min(10.0));
            let reaches = (0..=64).any(|k| {
                let t = t_end * f64::from(k) / 64.0;
                (0..3).all(|a| {
                    let p = f64::from(ray.o[a]) + t * f64::from(ray.d[a]);
                    f64::from(lo[a]) <= p && p <= f64::from(hi[a])
                })
            });
            let hit = mask & (1 << lane) != 0;
            if reaches {
                inside += 1;
                assert!(hit, "missed lane {lane} of {boxes:?} by {ray:?}");
                assert!(t_near[lane] >= 0.0);
            }
            // Control: a box entirely behind the origin along a nonzero axis is rejected.
            if (0..3).any(|a| {
                (ray.d[a] > 0.0 && hi[a] < ray.o[a] - 1e-3)
                    || (ray.d[a] < 0.0 && lo[a] > ray.o[a] + 1e-3)
                    || (ray.d[a] == 0.0 && (hi[a] < ray.o[a] - 1e-3 || lo[a] > ray.o[a] + 1e-3))
            }) {
                rejected += 1;
                assert!(
                    !hit,
                    "hit a box behind the ray: lane {lane} {boxes:?} {ray:?}"
                );
            }
        }
    }
    assert!(inside > 5_000 && rejected > 5_000, "{inside} {rejected}");
}

/// Every primitive is in exactly one leaf, and every child box contains what is below it.
#[test]
fn structure_covers_every_primitive_once() {
    let mut rng = Rng(13);
    for n in [1usize, 2, 5, 17, 1000, 20_000] {
        let boxes: Vec<Aabb> = random_soup(&mut rng, n)
            .iter()
            .map(|t| Aabb::point(t[0]).grow(t[1]).grow(t[2]))
            .collect();
        let (bvh, order) = Bvh4::build(&boxes);
        let mut seen = vec![0u32; n];
        let mut stack = vec![(0usize, bvh.bounds())];
        while let Some((i, outer)) = stack.pop() {
            let node = &bvh.nodes[i];
            assert!(node.used != 0 && (node.used & (node.used + 1)) == 0);
            for lane in 0..node.used.count_ones() as usize {
                let b = node.child_bounds(lane);
                assert_eq!(outer.union(b), outer, "child box outside its parent");
                if node.count[lane] == 0 {
                    stack.push((node.child[lane] as usize, b));
                } else {
                    let first = node.child[lane] as usize;
                    for k in first..first + node.count[lane] as usize {
                        let pb = boxes[order[k] as usize];
                        assert_eq!(b.union(pb), b, "primitive outside its leaf");
                        seen[order[k] as usize] += 1;
                    }
                }
            }
        }
        assert!(
            seen.iter().all(|&s| s == 1),
            "{n}: a primitive not in exactly one leaf"
        );
    }
}

/// Counted casts return exactly what the ordinary ones return, and count what they do: a ray
/// that misses the scene's box visits the root only; rays that hit reach at least one leaf.
#[test]
fn counted_casts_agree_and_count() {
    use tessera_core::accel::TraversalCounts;
    let mut rng = Rng(17);
    let s = scene(
        random_soup(&mut rng, 2000),
        vec![Sphere {
            center: Vec3::ZERO,
            radius: 2.0,
        }],
    );
    let mut c = TraversalCounts::default();
    let mut hits = 0;
    for ray in random_rays(&mut rng, 3000) {
        let h = s.intersect_hit(&ray);
        let mut one = TraversalCounts::default();
        let hc = s.intersect_hit_counted(&ray, &mut one);
        assert_eq!(
            h.map(|h| (h.t.to_bits(), h.prim)),
            hc.map(|h| (h.t.to_bits(), h.prim))
        );
        assert_eq!(s.occluded(&ray), s.occluded_counted(&ray, &mut one));
        if h.is_some() {
            hits += 1;
            assert!(one.leaves >= 1 && one.blocks >= one.leaves && one.nodes >= 1);
        }
        c.add(&one);
    }
    assert_eq!(c.rays, 6000);
    assert!(hits > 500 && c.nodes > c.rays, "{hits} {c:?}");
    // Control: a ray pointing away from everything tests the root's four boxes and nothing else.
    let away = Ray::new(Vec3::splat(100.0), Vec3::ONE);
    let mut one = TraversalCounts::default();
    assert!(s.intersect_hit_counted(&away, &mut one).is_none());
    assert_eq!((one.rays, one.nodes, one.leaves, one.blocks), (1, 1, 0, 0));
}

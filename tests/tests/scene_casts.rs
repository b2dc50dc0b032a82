//! The scene's own ray casts (`Scene::intersect_hit`, `Scene::occluded` and their counted
//! versions), whatever hierarchy it uses, against brute force (a loop over every primitive):
//! the same closest distance and primitive (up to exact ties) and the same any-hit answer on
//! triangle soups with degenerate triangles and spheres, on an empty scene and on scenes of a
//! single primitive; counted casts return what the ordinary ones return and count the work.
//! Controls: a ray stopped short of the one triangle must miss it, and a ray pointing away from
//! everything must visit the root only. Axis-parallel rays on box planes are checked with the
//! BVH in `bvh8.rs`, which also runs these checks on them.
use tessera_core::accel::TraversalCounts;
use tessera_core::geometry::Sphere;
use tessera_core::glam::Vec3;
use tessera_core::math::Ray;

use tessera_tests::rng::SplitMix as Rng;
use tessera_tests::soup::{check_scene_casts, random_rays, random_soup, random_soup_scene, scene};

#[test]
fn agree_with_brute_force_on_soups() {
    let mut rng = Rng(7);
    let mut hits = 0;
    for n in [1usize, 2, 3, 4, 5, 9, 64, 500, 5000] {
        let s = random_soup_scene(&mut rng, n);
        let rays = random_rays(&mut rng, 3000);
        hits += check_scene_casts(&s, &rays);
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
    check_scene_casts(&one, &rays);
    check_scene_casts(&sphere, &rays);
}

/// Counted casts return exactly what the ordinary ones return, and count what they do: a ray
/// that misses the scene's box visits the root only; rays that hit reach at least one leaf.
#[test]
fn counted_casts_agree_and_count() {
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
    // Control: a ray pointing away from everything tests the root's boxes and nothing else.
    let away = Ray::new(Vec3::splat(100.0), Vec3::ONE);
    let mut one = TraversalCounts::default();
    assert!(s.intersect_hit_counted(&away, &mut one).is_none());
    assert_eq!((one.rays, one.nodes, one.leaves, one.blocks), (1, 1, 0, 0));
}

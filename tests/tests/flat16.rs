//! The sixteen-lane casts of one-node scenes (`core/src/accel/flat16.rs`, AVX-512 CPUs): where
//! they decide, they give the general walk's answer bit for bit (distance, primitive,
//! barycentrics; any hit), and they decide nearly every ray; where they cannot vouch for the
//! walk's answer (exact ties, rounding at a lowered `t_max`, edge functions of zero) they say so.
//! The scenes: the Cornell box (32 triangles, the case this is for) with rays from inside, from
//! its surfaces, toward its corners and edges and along its axes, and random triangle soups of up
//! to 32 triangles against brute force. Renders with and without the fast casts give the same
//! image bits. Scenes it does not fit (33 triangles, a sphere, several nodes) do not get one.
//!
//! On a CPU without AVX-512 no scene gets the fast casts; the tests then check only that.
use tessera_core::accel::{tri4::Ray4, Avx512};
use tessera_core::geometry::{Hit, Sphere};
use tessera_core::glam::Vec3;
use tessera_core::math::{Norm, Ray};
use tessera_core::scene::Scene;
use tessera_tests::rng::SplitMix as Rng;
use tessera_tests::soup::{check_scene_casts, random_rays, random_soup, scene};
use tessera_tests::{load_file, render_loaded};

/// The walk's answer (the scene without its fast casts).
fn walk(s: &Scene) -> Scene {
    let mut w = s.clone();
    w.flat = None;
    w
}

fn bits(h: Option<Hit>) -> Option<(u32, u32, u32, u32)> {
    h.map(|h| (h.t.to_bits(), h.prim, h.uv.x.to_bits(), h.uv.y.to_bits()))
}

/// Compares the fast casts with the walk's on `rays`; returns how many closest-hit casts and
/// any-hit casts the fast path left undecided.
fn compare(s: &Scene, w: &Scene, rays: &[Ray]) -> (usize, usize) {
    let flat = s.flat.as_ref().expect("the scene has fast casts");
    let (mut closest_left, mut any_left) = (0, 0);
    for ray in rays {
        let r4 = Ray4::from_ray(ray);
        let expect = w.intersect_hit(ray);
        match flat.closest(ray, &r4) {
            Some(got) => assert_eq!(bits(got), bits(expect), "closest hit for {ray:?}"),
            None => closest_left += 1,
        }
        assert_eq!(
            bits(s.intersect_hit(ray)),
            bits(expect),
            "scene cast {ray:?}"
        );
        let blocked = w.occluded(ray);
        match flat.any(ray, &r4) {
            Some(got) => assert_eq!(got, blocked, "any hit for {ray:?}"),
            None => any_left += 1,
        }
        assert_eq!(s.occluded(ray), blocked, "scene any hit {ray:?}");
    }
    (closest_left, any_left)
}

fn cbox() -> Scene {
    load_file("cbox.xml", &[("res", "24"), ("rfilter", "box")]).scene
}

/// The corners of every triangle of the scene.
fn corners(s: &Scene) -> Vec<[Vec3; 3]> {
    (0..s.prims.len()).filter_map(|i| s.triangle(i)).collect()
}

#[test]
fn cbox_casts_match_the_walk_and_decide_nearly_always() {
    let s = cbox();
    if Avx512::detect().is_none() {
        assert!(s.flat.is_none());
        eprintln!("no AVX-512 here: nothing else to check");
        return;
    }
    assert!(s.flat.is_some(), "cbox (32 triangles, one node) qualifies");
    let w = walk(&s);
    let b = s.bounds();
    let mut rng = Rng(11);
    let inside = |rng: &mut Rng| b.min + (b.max - b.min) * Vec3::new(rng.f(), rng.f(), rng.f());
    let dir = |rng: &mut Rng| loop {
        let d = rng.v(2.0);
        if d.norm() > 0.1 {
            return d.unit();
        }
    };
    // Rays from inside the box, some with a short extent, and rays leaving points of its surfaces
    // (as continuation and shadow rays do: origins a little off the surface, toward a point).
    let mut rays = Vec::new();
    for i in 0..40_000 {
        let mut ray = Ray::new(inside(&mut rng), dir(&mut rng));
        if i % 3 == 0 {
            ray.t_max = rng.f() * 6.0;
        }
        rays.push(ray);
    }
    let tris = corners(&s);
    for _ in 0..40_000 {
        let [p0, p1, p2] = tris[rng.below(tris.len())];
        let (u, v) = (rng.f(), rng.f());
        let (u, v) = if u + v > 1.0 {
            (1.0 - u, 1.0 - v)
        } else {
            (u, v)
        };
        let p = p0 + (p1 - p0) * u + (p2 - p0) * v;
        let n = (p1 - p0).cross(p2 - p0).unit();
        let side = if rng.f() < 0.5 { n } else { -n };
        let o = p + side * 1e-4;
        let target = inside(&mut rng);
        let mut ray = Ray::new(o, (target - o).unit());
        if rng.f() < 0.5 {
            // A shadow ray: stops just short of its target.
            ray.t_max = (target - o).norm() * (1.0 - 1e-4);
        }
        rays.push(ray);
    }
    let (closest_left, any_left) = compare(&s, &w, &rays);
    let n = rays.len();
    eprintln!("left to the walk: {closest_left} closest, {any_left} any hit of {n}");
    assert!(
        closest_left * 200 < n && any_left * 200 < n,
        "the fast path left {closest_left} closest and {any_left} any-hit casts of {n} to the walk"
    );
}

/// Rays aimed at the corners and edge midpoints of the box's triangles (where neighbours meet and
/// distances tie), and along the axes: the fast path may leave them to the walk, but what it
/// decides is the walk's answer; and such rays do reach the undecided cases.
#[test]
fn cbox_edges_corners_and_axes() {
    let s = cbox();
    if s.flat.is_none() {
        return;
    }
    let w = walk(&s);
    let b = s.bounds();
    let c = (b.min + b.max) * 0.5;
    let mut rays = Vec::new();
    let mut targets = Vec::new();
    for [p0, p1, p2] in corners(&s) {
        targets.extend([
            p0,
            p1,
            p2,
            (p0 + p1) * 0.5,
            (p1 + p2) * 0.5,
            (p2 + p0) * 0.5,
        ]);
    }
    let mut rng = Rng(5);
    for t in &targets {
        for _ in 0..8 {
            let o = c + rng.v(2.0);
            rays.push(Ray::new(o, (*t - o).unit()));
        }
    }
    for a in 0..3 {
        for sign in [1.0, -1.0] {
            let mut d = Vec3::ZERO;
            d[a] = sign;
            for _ in 0..200 {
                rays.push(Ray::new(c + rng.v(4.0), d));
            }
        }
    }
    let (closest_left, any_left) = compare(&s, &w, &rays);
    eprintln!(
        "left to the walk: {closest_left} closest, {any_left} any hit of {}",
        rays.len()
    );
    assert!(
        closest_left > 0,
        "rays at shared edges and corners should reach an undecided case"
    );
}

/// Soups of up to 32 triangles (degenerate ones among them): against brute force, and bit for
/// bit against the walk.
#[test]
fn small_soups_match_brute_force_and_the_walk() {
    if Avx512::detect().is_none() {
        return;
    }
    let mut rng = Rng(23);
    let mut fast = 0;
    for n in [1usize, 3, 4, 5, 8, 15, 16, 17, 24, 31, 32] {
        for _ in 0..4 {
            let s = scene(random_soup(&mut rng, n), vec![]);
            let rays = random_rays(&mut rng, 2000);
            if s.flat.is_none() {
                // Only a soup the build splits into several nodes goes without.
                assert!(s.bvh.nodes.len() > 1, "{n} triangles in one node");
                continue;
            }
            fast += 1;
            check_scene_casts(&s, &rays);
            compare(&s, &walk(&s), &rays);
        }
    }
    eprintln!("{fast} of 44 soups had fast casts");
    assert!(fast >= 30, "only {fast} of 44 soups had fast casts");
}

#[test]
fn scenes_it_does_not_fit_have_none() {
    let mut rng = Rng(29);
    let too_many = scene(random_soup(&mut rng, 33), vec![]);
    assert!(too_many.flat.is_none());
    let sphere = Sphere {
        center: Vec3::ZERO,
        radius: 1.0,
    };
    let soup8 = random_soup(&mut rng, 8);
    let with_sphere = scene(soup8.clone(), vec![sphere]);
    assert_eq!(with_sphere.bvh.nodes.len(), 1);
    assert!(with_sphere.flat.is_none());
    if Avx512::detect().is_some() {
        // Control: the same soup without the sphere qualifies.
        let soup = scene(soup8, vec![]);
        assert!(soup.flat.is_some());
    }
}

/// The same image bits with and without the fast casts (both samplers).
#[test]
fn cbox_renders_the_same_bits_without_the_fast_casts() {
    for sampler in ["independent", "zsobol"] {
        let mut l = load_file("cbox.xml", &[("res", "24"), ("rfilter", "box")]);
        l.set_sampler(Some(sampler), 8).expect("a known sampler");
        let with = render_loaded(&l, 8, 3);
        l.scene.flat = None;
        let without = render_loaded(&l, 8, 3);
        for (i, (p, q)) in with.pixels.iter().zip(&without.pixels).enumerate() {
            let bits = |a: &tessera_core::film::PixelAccum| {
                (a.sum.map(f64::to_bits), a.sum_sq.map(f64::to_bits), a.count)
            };
            assert!(bits(p) == bits(q), "{sampler}: pixel {i} differs");
        }
    }
}

/// Pairs of nearly coincident triangles (each a copy of another with corners moved by a few
/// units in the last place), so hit distances tie or differ by an ulp or two: the cases where
/// the walk's answer rests on the re-check at a lowered `t_max` and on the leaves' entry
/// distances. What the fast path decides there must still be the walk's answer.
#[test]
fn nearly_coincident_pairs_match_the_walk() {
    if Avx512::detect().is_none() {
        return;
    }
    let mut rng = Rng(31);
    let nudge = |x: f32, k: i32| f32::from_bits((x.to_bits() as i32 + k) as u32);
    let (mut decided, mut total) = (0, 0);
    for set in 0..40 {
        // Half the sets lie in planes of constant x, y or z (as the Cornell box's walls), where
        // a triangle's hit and its leaf's entry distance are one rounding apart.
        let flat_axis = (set % 2 == 0).then_some(set / 2 % 3);
        let mut tris = Vec::new();
        for _ in 0..16 {
            let c = rng.v(10.0);
            let mut t = [c + rng.v(6.0), c + rng.v(6.0), c + rng.v(6.0)];
            if let Some(a) = flat_axis {
                for p in &mut t {
                    p[a] = c[a];
                }
            }
            let mut u = t;
            let k = rng.below(5) as i32 - 2;
            for p in &mut u {
                for a in 0..3 {
                    p[a] = match flat_axis {
                        Some(f) if f == a => nudge(p[a], k),
                        _ => nudge(p[a], rng.below(7) as i32 - 3),
                    };
                }
            }
            tris.push(t);
            tris.push(u);
        }
        let s = scene(tris, vec![]);
        if s.flat.is_none() {
            continue;
        }
        let rays = random_rays(&mut rng, 5000);
        let (left, _) = compare(&s, &walk(&s), &rays);
        total += rays.len();
        decided += rays.len() - left;
    }
    eprintln!("decided {decided} of {total}");
    assert!(
        total >= 40_000 && decided * 2 > total,
        "{decided} of {total}"
    );
}

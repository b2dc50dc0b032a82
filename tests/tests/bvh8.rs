//! The 8-wide BVH and its AVX2 box test: closest hits (distance bits and primitive) equal
//! brute force's on triangle soups with spheres, a bumpy sphere mesh and axis-parallel rays on
//! box planes, with the AVX2 and the portable test, with the greedy and the surface-area
//! collapse, and with the scene's own casts (leaves inside the AVX2 walk, restarted with a
//! larger stack when the small one overflows); any hit agrees; the AVX2, two-SSE-halves and
//! scalar eight-box tests give the same bits, and the scalar one is conservative against an
//! independent f64 check; structure invariants; counted walks. Controls: a hierarchy with one
//! child box shrunk must disagree with brute force, and the box tests must reject boxes behind
//! the ray. The comparison harness is `tessera_tests::wide`; soups of spheres and disks (leaves
//! with and without triangles) are tested in `bvh8_mixed.rs`, the scene's casts on their own in
//! `scene_casts.rs`.
use tessera_core::accel::slab::{RayPre, MAX_X, MIN_X};
use tessera_core::accel::slab_simd::{hit8_scalar, Avx2, Boxes8, Hit8, Portable, WithHit8};
use tessera_core::accel::tri_block::Ray4;
use tessera_core::accel::{AnyLeaves, Bvh, Bvh8, ClosestLeaves, Collapse, Leaves};
use tessera_core::geometry::{Hit, TriRay};
use tessera_core::glam::Vec3;
use tessera_core::math::{Aabb, Norm, Ray};

use tessera_tests::rng::SplitMix as Rng;
use tessera_tests::soup::{
    check_scene_casts, mesh_scene, random_rays, random_soup, random_soup_scene, scene,
};
use tessera_tests::wide::{compare, WideScene};

#[test]
fn agrees_with_brute_force_on_soups() {
    let mut rng = Rng(21);
    let mut hits = 0;
    for n in [1usize, 2, 7, 8, 9, 33, 64, 500, 5000] {
        let s = random_soup_scene(&mut rng, n);
        let w8 = WideScene::<Bvh8>::new(&s);
        let rays = random_rays(&mut rng, 2000);
        let (h, bad) = compare(&s, &w8, &rays);
        assert_eq!(bad, 0, "{n} triangles: {bad} rays disagree");
        hits += h;
    }
    assert!(hits > 2000, "too few hits ({hits}) to mean anything");
}

/// A bumpy sphere (latitude-longitude grid, radially displaced), rays from inside and outside.
#[test]
fn agrees_on_a_bumpy_sphere() {
    let (nu, nv) = (120usize, 60usize);
    let mut positions = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            let (u, v) = (i as f32 / nu as f32, j as f32 / nv as f32);
            let (phi, theta) = (u * std::f32::consts::TAU, v * std::f32::consts::PI);
            let d = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            let r = 1.0 + 0.08 * (9.0 * d.x).sin() * (7.0 * d.y).sin() * (5.0 * d.z).sin();
            positions.push(d * r);
        }
    }
    let id = |i: usize, j: usize| (j * (nu + 1) + i) as u32;
    let mut indices = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            indices.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
            indices.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let s = mesh_scene(positions, indices, vec![]);
    let mut rng = Rng(23);
    let rays: Vec<Ray> = (0..4000)
        .map(|k| {
            let o = if k % 2 == 0 { rng.v(1.6) } else { rng.v(8.0) };
            let d = (rng.v(2.0) - o * 0.3).unit();
            Ray::new(o, d)
        })
        .collect();
    let mut w8 = WideScene::<Bvh8>::new(&s);
    let (hits, bad) = compare(&s, &w8, &rays);
    assert_eq!(bad, 0, "{bad} rays disagree");
    assert!(hits > 2000, "too few hits ({hits})");

    // Control: shrink one child box of the root to nothing; rays into it must now be missed.
    let root = &mut w8.bvh.nodes[0];
    for a in 0..3 {
        root.boxes.b[MIN_X + a][0] = f32::INFINITY;
        root.boxes.b[MAX_X + a][0] = f32::NEG_INFINITY;
    }
    let (_, bad) = compare(&s, &w8, &rays);
    assert!(
        bad > 100,
        "a broken hierarchy went unnoticed ({bad} rays disagree)"
    );
}

/// Axis-aligned quads on an integer grid, rays along the axes (zero direction components, also
/// negative zeros) starting on grid planes: slab distances `0 * inf` are NaN and must not cull.
/// Checked through the harness and, primitive by primitive, through the scene's casts.
#[test]
fn axis_parallel_rays_on_box_planes() {
    let mut tris = Vec::new();
    for i in 0..6 {
        for j in 0..6 {
            let (x, y, z) = (i as f32, j as f32, ((i * 7 + j * 3) % 5) as f32);
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
    let mut rng = Rng(29);
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
        let mut c = || match rng.below_scaled(3) {
            0 => rng.below_scaled(8) as f32 - 1.0,
            1 => rng.below_scaled(16) as f32 * 0.5 - 1.0,
            _ => rng.f() * 8.0 - 1.0,
        };
        let o = Vec3::new(c(), c(), c());
        rays.push(Ray::new(o, dirs[rng.below_scaled(dirs.len())]));
    }
    let w8 = WideScene::<Bvh8>::new(&s);
    let (hits, bad) = compare(&s, &w8, &rays);
    assert_eq!(bad, 0, "{bad} rays disagree");
    assert!(hits > 300, "too few hits ({hits})");
    assert_eq!(check_scene_casts(&s, &rays), hits);
}

fn random_boxes(rng: &mut Rng) -> Boxes8 {
    let mut b = Boxes8::EMPTY;
    for lane in 0..rng.below_scaled(9) {
        for a in 0..3 {
            let (p, q) = match rng.below_scaled(5) {
                0 => (0.0, rng.f()),
                1 => {
                    let p = rng.f() - 0.5;
                    (p, p)
                }
                2 => (f32::NEG_INFINITY, rng.f()),
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
    match rng.below_scaled(4) {
        0 => ray.t_max = rng.f() * 3.0,
        1 => ray.t_max = f32::INFINITY,
        _ => {}
    }
    ray
}

/// One box test, to run compiled with AVX2.
struct Test8<'a>(&'a Boxes8, &'a RayPre, f32);

impl WithHit8 for Test8<'_> {
    type Output = (u32, [f32; 8]);
    #[inline(always)]
    fn call<H: Hit8>(self, test: H) -> Self::Output {
        test.hit8(self.0, self.1, self.2)
    }
}

#[test]
fn avx2_portable_and_scalar_box_tests_give_the_same_bits() {
    let avx2 = Avx2::detect();
    if avx2.is_none() {
        eprintln!("no AVX2 on this CPU: comparing the portable and scalar tests only");
    }
    let mut rng = Rng(31);
    let (mut hits, mut rejected) = (0, 0);
    for _ in 0..200_000 {
        let boxes = random_boxes(&mut rng);
        let ray = random_box_ray(&mut rng);
        let pre = RayPre::new(&ray);
        let (ms, ts) = hit8_scalar(&boxes, &pre, ray.t_max);
        let mut results = vec![Portable.hit8(&boxes, &pre, ray.t_max)];
        if let Some(a) = avx2 {
            results.push(a.hit8(&boxes, &pre, ray.t_max));
            results.push(a.run(Test8(&boxes, &pre, ray.t_max)));
        }
        for (m, t) in results {
            assert_eq!(m, ms, "masks differ for {ray:?} {boxes:?}");
            for lane in 0..8 {
                assert_eq!(t[lane].to_bits(), ts[lane].to_bits(), "t_near differs");
            }
        }
        for lane in 0..8 {
            let hit = ms & (1 << lane) != 0;
            assert!(!hit || !ts[lane].is_nan(), "NaN entry distance");
            let b = &boxes.b;
            // Control: a box entirely behind the origin along a nonzero axis is rejected.
            if (0..3).any(|a| {
                (ray.d[a] > 0.0 && b[MAX_X + a][lane] < ray.o[a] - 1e-3)
                    || (ray.d[a] < 0.0 && b[MIN_X + a][lane] > ray.o[a] + 1e-3)
            }) {
                rejected += 1;
                assert!(!hit, "hit a box behind the ray: {ray:?} {boxes:?}");
            }
        }
        hits += ms.count_ones();
    }
    assert!(hits > 50_000 && rejected > 50_000, "{hits} {rejected}");
}

/// The portable eight-box test (whose bits the AVX2 and SSE-halves tests give, see above) never
/// misses a box the ray passes through (checked in f64 by points along the ray inside the box),
/// and rejects boxes the ray clearly misses.
#[test]
fn scalar_box_test_is_conservative_and_rejects_misses() {
    let mut rng = Rng(9);
    let (mut inside, mut rejected) = (0, 0);
    for _ in 0..100_000 {
        let boxes = random_boxes(&mut rng);
        let ray = random_box_ray(&mut rng);
        let (mask, t_near) = hit8_scalar(&boxes, &RayPre::new(&ray), ray.t_max);
        for lane in 0..8 {
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
            // Control: a box entirely behind the origin along a nonzero axis, or beside it along
            // an axis the ray is parallel to, is rejected. (Beside it: only when the box is
            // bounded or the ray is. Otherwise every slab may give entry and exit at infinity,
            // and `inf <= inf` is a hit: conservative, and never met by a scene's finite boxes.)
            let bounded = ray.t_max.is_finite() || lo.iter().chain(&hi).all(|x| x.is_finite());
            if (0..3).any(|a| {
                (ray.d[a] > 0.0 && hi[a] < ray.o[a] - 1e-3)
                    || (ray.d[a] < 0.0 && lo[a] > ray.o[a] + 1e-3)
                    || (ray.d[a] == 0.0
                        && bounded
                        && (hi[a] < ray.o[a] - 1e-3 || lo[a] > ray.o[a] + 1e-3))
            }) {
                rejected += 1;
                assert!(
                    !hit,
                    "hit a box behind the ray: lane {lane} {boxes:?} {ray:?}"
                );
            }
        }
    }
    assert!(inside > 40_000 && rejected > 300_000, "{inside} {rejected}");
}

/// Nodes on the longest root-to-leaf path below binary node `at`.
fn binary_depth(bin: &Bvh, at: usize) -> usize {
    let n = &bin.nodes[at];
    if n.count > 0 {
        1
    } else {
        1 + binary_depth(bin, at + 1).max(binary_depth(bin, n.offset as usize))
    }
}

/// Every primitive is in exactly one leaf, every child box contains what is below it; the
/// primitive order is the binary build's, and on large soups nodes hold more children than a
/// 4-wide node could and paths are at most half as long as the binary tree's.
#[test]
fn structure_covers_every_primitive_once() {
    let mut rng = Rng(37);
    for n in [1usize, 2, 5, 17, 1000, 20_000] {
        let boxes: Vec<Aabb> = random_soup(&mut rng, n)
            .iter()
            .map(|t| Aabb::point(t[0]).grow(t[1]).grow(t[2]))
            .collect();
        let (bvh, order) = Bvh8::build(&boxes);
        let (bin, bin_order) = Bvh::build_with(&boxes, Bvh8::PARAMS);
        assert_eq!(
            order, bin_order,
            "collapsed from the binary build: same primitive order"
        );
        let bin_depth = binary_depth(&bin, 0);
        assert!(bvh.depth() <= bin_depth);
        let mut seen = vec![0u32; n];
        let mut stack = vec![(0usize, bvh.bounds())];
        while let Some((i, outer)) = stack.pop() {
            let node = &bvh.nodes[i];
            assert!(node.used != 0 && (node.used & (node.used + 1)) == 0);
            assert_eq!(node.leaves & !node.used, 0, "leaf bit on an unused lane");
            for lane in 0..node.used.count_ones() as usize {
                let b = node.child_bounds(lane);
                assert_eq!((node.leaves >> lane) & 1 == 1, node.count[lane] > 0);
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
        assert!(seen.iter().all(|&s| s == 1), "{n}: not in exactly one leaf");
        if n >= 1000 {
            let fill = |lanes: u32, nodes: usize| f64::from(lanes) / nodes as f64;
            let f8 = fill(
                bvh.nodes.iter().map(|n| n.used.count_ones()).sum(),
                bvh.nodes.len(),
            );
            let depth = bvh.depth();
            eprintln!("{n}: children per node {f8:.2}, depth {depth} (binary {bin_depth})");
            assert!(f8 > 4.0, "nodes not fuller than 4-wide ones could be: {f8}");
            assert!(2 * depth <= bin_depth, "depth {depth}, binary {bin_depth}");
        }
    }
}

/// Counted walks visit nodes; a ray pointing away from everything visits the root only.
#[test]
fn counted_walks_count_nodes() {
    let mut rng = Rng(41);
    let s = scene(random_soup(&mut rng, 3000), vec![]);
    let w8 = WideScene::<Bvh8>::new(&s);
    let mut hits = 0;
    for ray in random_rays(&mut rng, 1000) {
        let mut nodes = 0;
        if w8.intersect_hit(&ray, Some(&mut nodes)).is_some() {
            hits += 1;
            assert!(nodes >= 2, "a hit below the root visits more than the root");
        }
    }
    assert!(hits > 100);
    let away = Ray::new(Vec3::splat(100.0), Vec3::ONE);
    let mut nodes = 0;
    assert!(w8.intersect_hit(&away, Some(&mut nodes)).is_none());
    assert_eq!(nodes, 1);
    assert!(!w8.occluded(&away, Some(&mut nodes)));
    assert_eq!(nodes, 2);
}

/// Leaves that record each leaf they are asked to test, then test it as the scene's do;
/// `R` says whether the walk may restart (a small stack first).
struct Recording<'a, F, const R: bool> {
    inner: ClosestLeaves<'a, F>,
    calls: usize,
}

impl<F, const R: bool> Leaves for Recording<'_, F, R>
where
    F: FnMut(usize, &[Vec3; 3], f32) -> Option<(f32, tessera_core::glam::Vec2)>,
{
    const RESTARTABLE: bool = R;

    fn test<H: Hit8>(&mut self, simd: H, first: usize, count: usize, t_max: f32) -> Option<f32> {
        self.calls += 1;
        self.inner.test(simd, first, count, t_max)
    }
}

/// Rays that meet many overlapping boxes overflow the small stack a restartable cast tries first
/// (seen as leaves tested again after the restart); their closest hit, and the any-hit answer,
/// equal the non-restarting walk's and brute force's.
#[test]
fn restarted_casts_agree() {
    let mut rng = Rng(61);
    // Big overlapping triangles: most boxes overlap most rays.
    let tris: Vec<[Vec3; 3]> = (0..4000)
        .map(|_| {
            let c = rng.v(6.0);
            [c + rng.v(6.0), c + rng.v(6.0), c + rng.v(6.0)]
        })
        .collect();
    let s = scene(tris, vec![]);
    let (mut restarted, mut hits) = (0, 0);
    for ray in random_rays(&mut rng, 3000) {
        let tri = TriRay::new(&ray);
        let r4 = Ray4::new(&tri);
        let other = |_: usize, _: &[Vec3; 3], _: f32| None;
        let mut best = [None, None];
        let mut calls = [0, 0];
        let mut small = Recording::<_, true> {
            inner: ClosestLeaves {
                blocks: &s.blocks,
                ray: &r4,
                best: &mut best[0],
                other,
            },
            calls: 0,
        };
        s.bvh.cast::<false>(&ray, &mut small);
        calls[0] = small.calls;
        let mut plain = Recording::<_, false> {
            inner: ClosestLeaves {
                blocks: &s.blocks,
                ray: &r4,
                best: &mut best[1],
                other,
            },
            calls: 0,
        };
        s.bvh.cast::<false>(&ray, &mut plain);
        calls[1] = plain.calls;
        let key = |h: &Option<Hit>| h.map(|h| (h.t.to_bits(), h.prim));
        assert_eq!(key(&best[0]), key(&best[1]), "{ray:?}");
        let brute = (0..s.prims.len())
            .filter_map(|i| s.intersect_prim(i, &ray, &tri, ray.t_max))
            .map(|(t, _)| t)
            .fold(None, |m: Option<f32>, t| Some(m.map_or(t, |m| m.min(t))));
        assert_eq!(best[0].map(|h| h.t), brute);
        let mut any = AnyLeaves {
            blocks: &s.blocks,
            ray: &r4,
            hit: false,
            other,
        };
        s.bvh.cast::<true>(&ray, &mut any);
        assert_eq!(any.hit, brute.is_some());
        assert!(calls[0] >= calls[1]);
        restarted += usize::from(calls[0] > calls[1]);
        hits += usize::from(brute.is_some());
    }
    eprintln!("{restarted} of 3000 rays restarted, {hits} hit");
    assert!(
        restarted > 30 && hits > 1000,
        "{restarted} restarts, {hits} hits"
    );
}

/// The surface-area collapse fills nodes better than the greedy one and costs less by its own
/// measure; both cover every primitive once (`structure_covers_every_primitive_once` checks the
/// default, this the greedy one through `compare`).
#[test]
fn surface_area_collapse_fills_nodes_better() {
    let mut rng = Rng(71);
    let boxes: Vec<Aabb> = random_soup(&mut rng, 20_000)
        .iter()
        .map(|t| Aabb::point(t[0]).grow(t[1]).grow(t[2]))
        .collect();
    let (bin, _) = Bvh::build_with(&boxes, Bvh8::PARAMS);
    let fill = |b: &Bvh8| {
        f64::from(b.nodes.iter().map(|n| n.used.count_ones()).sum::<u32>()) / b.nodes.len() as f64
    };
    let greedy = Bvh8::from_binary_with(&bin, Collapse::Greedy);
    let sah = Bvh8::from_binary_with(&bin, Collapse::DEFAULT);
    let (fg, fs) = (fill(&greedy), fill(&sah));
    eprintln!("children per node: greedy {fg:.2}, surface-area {fs:.2}");
    assert!(fs > fg + 0.5, "{fs} vs {fg}");
    assert!(sah.nodes.len() < greedy.nodes.len());
    // Deterministic: the same tree bit for bit when built again.
    let again = Bvh8::from_binary_with(&bin, Collapse::DEFAULT);
    assert!(sah
        .nodes
        .iter()
        .zip(&again.nodes)
        .all(|(a, b)| a.boxes == b.boxes && a.child == b.child && a.count == b.count));
}

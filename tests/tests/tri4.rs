//! The four-lane triangle test (`accel::tri_block`) against the scalar watertight test: every lane
//! gives the same hit or miss, distance and barycentrics, bit for bit, as `TriRay::intersect`
//! (with the scalar test run for the lanes the vector code hands back); the SSE and portable
//! versions agree bit for bit; re-checking a hit against a smaller `t_max` (`Lanes::accepts`)
//! agrees with the scalar test at that `t_max`. Cases: random triangles and rays, shared edges
//! and vertices hit exactly, axis-aligned geometry and rays with zero direction components,
//! degenerate triangles, coordinates from 1e-38 to 1e38, infinite and NaN corners, and `t_max`
//! on, just above and just below the hit distance. Controls show that a 1-ulp change of one
//! result, and a different but equivalent-looking formula (`t_scaled / det`), are caught.
use tessera_core::accel::slab_simd::{Avx2, Hit8, Portable};
use tessera_core::accel::tri_block::{test4, test4_scalar, Lanes, Ray4, Tri4};
use tessera_core::accel::tri_block_pair::{test8_portable, Lanes8};
use tessera_core::geometry::TriRay;
use tessera_core::glam::Vec3;
use tessera_core::math::Ray;

use tessera_tests::rng::SplitMix as Rng;

type Tris = [[Vec3; 3]; 4];
type Found = Option<(f32, f32, f32, f32)>;

fn block(t: &Tris) -> Tri4 {
    let mut b = Tri4::EMPTY;
    for (lane, c) in t.iter().enumerate() {
        b.set(lane, c);
    }
    b
}

/// One test case: four triangles, a ray and its `t_max`.
fn case(rng: &mut Rng, kind: usize) -> (Tris, Ray) {
    let mut t: Tris = [[Vec3::ZERO; 3]; 4];
    let random_dir = |rng: &mut Rng| loop {
        let d = rng.v(2.0);
        if d != Vec3::ZERO {
            break d;
        }
    };
    // A point inside one of the triangles (random barycentrics), for rays that should hit.
    let aim = |rng: &mut Rng, t: &Tris| {
        let [p0, p1, p2] = t[rng.below(4)];
        let (u, v) = (rng.f(), rng.f());
        let (u, v) = if u + v > 1.0 {
            (1.0 - u, 1.0 - v)
        } else {
            (u, v)
        };
        p0 + (p1 - p0) * u + (p2 - p0) * v
    };
    let (o, d) = match kind {
        // Random triangles, a ray from outside through their region.
        0 => {
            for tri in &mut t {
                let c = rng.v(2.0);
                *tri = [c + rng.v(1.5), c + rng.v(1.5), c + rng.v(1.5)];
            }
            let o = rng.v(10.0);
            (o, aim(rng, &t) - o)
        }
        // A quad split in two (lanes 0, 1) and a fan around its corner (lanes 2, 3); the ray
        // aims exactly at a shared vertex, an edge midpoint, or an edge third.
        1 => {
            let p = rng.v(4.0);
            let (u, v, w) = (rng.v(2.0), rng.v(2.0), rng.v(2.0));
            t[0] = [p, p + u, p + v];
            t[1] = [p + u, p + u + v, p + v];
            t[2] = [p, p + v, p + w];
            t[3] = [p, p + w, p + u];
            let target = match rng.below(5) {
                0 => p,
                1 => p + u,
                2 => p + (u + v) * 0.5,
                3 => p + u + (v - u) * (1.0 / 3.0),
                _ => p + v * 0.5,
            };
            let o = target + rng.v(10.0);
            (o, target - o)
        }
        // Axis-aligned unit triangles on an integer grid, axis-aligned rays (also -0 components)
        // from grid points, so edge functions are exactly zero and origins lie on planes.
        2 => {
            let g = |rng: &mut Rng| (rng.below(5) as f32 - 2.0) * 0.5;
            for tri in &mut t {
                let p = Vec3::new(g(rng), g(rng), g(rng));
                let (a, b) = match rng.below(3) {
                    0 => (Vec3::X, Vec3::Y),
                    1 => (Vec3::Y, Vec3::Z),
                    _ => (Vec3::Z, Vec3::X),
                };
                *tri = [p, p + a, p + b];
            }
            let jitter = match rng.below(3) {
                0 => Vec3::ZERO,
                1 => Vec3::splat(0.25),
                _ => rng.v(0.5),
            };
            let o = Vec3::new(g(rng), g(rng), g(rng)) + jitter;
            let dirs = [
                Vec3::X,
                -Vec3::Y,
                Vec3::Z,
                Vec3::new(-0.0, 0.0, -1.0),
                Vec3::new(1.0, -0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, -1.0, 1.0),
                Vec3::new(1.0, 1.0, 1.0),
            ];
            (o, dirs[rng.below(dirs.len())])
        }
        // Degenerate triangles: a point, collinear corners, a repeated corner, a sliver.
        3 => {
            let c = rng.v(2.0);
            let e = rng.v(1.0);
            t[0] = [c, c, c];
            t[1] = [c, c + e, c + 2.0 * e];
            t[2] = [c, c + e, c + e];
            t[3] = [c, c + e, c + e + Vec3::splat(1e-7)];
            t.swap(0, rng.below(4));
            let target = c + e * rng.f();
            let o = target + rng.v(6.0);
            (o, target - o)
        }
        // Huge and tiny scales, far from the origin or not.
        4 => {
            let s = 10f32.powi(rng.below(77) as i32 - 38);
            let off = if rng.below(2) == 0 {
                Vec3::ZERO
            } else {
                rng.v(2.0) * s * 10f32.powi(rng.below(6) as i32)
            };
            for tri in &mut t {
                let c = rng.v(2.0);
                *tri = [c + rng.v(1.5), c + rng.v(1.5), c + rng.v(1.5)].map(|p| p * s + off);
            }
            let o = rng.v(10.0) * s + off;
            let d = (aim(rng, &t) - o) * 10f32.powi(rng.below(21) as i32 - 10);
            (o, if d == Vec3::ZERO { Vec3::Z } else { d })
        }
        // Infinite and NaN corners, and coordinates at f32::MAX.
        5 => {
            for tri in &mut t {
                let c = rng.v(2.0);
                *tri = [c + rng.v(1.5), c + rng.v(1.5), c + rng.v(1.5)];
            }
            let bad = [
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::NAN,
                f32::MAX,
                -f32::MAX,
                1e30,
            ];
            for _ in 0..1 + rng.below(3) {
                let (l, c, a) = (rng.below(4), rng.below(3), rng.below(3));
                t[l][c][a] = bad[rng.below(bad.len())];
            }
            let o = rng.v(10.0);
            (o, aim(rng, &t) - o)
        }
        // Direction lengths from 1e-20 to 1e20.
        _ => {
            for tri in &mut t {
                let c = rng.v(2.0);
                *tri = [c + rng.v(1.5), c + rng.v(1.5), c + rng.v(1.5)];
            }
            let o = rng.v(10.0);
            let d = if rng.below(4) == 0 {
                random_dir(rng)
            } else {
                aim(rng, &t) - o
            };
            let d = d * 10f32.powi(rng.below(41) as i32 - 20);
            (o, if d == Vec3::ZERO { Vec3::X } else { d })
        }
    };
    let mut ray = Ray::new(o, d);
    // t_max: unbounded, or around a lane's exact hit distance: on it, one ulp either side, or
    // a random fraction of it (zero, tiny, huge or NaN when the lane is missed).
    let tri = TriRay::new(&ray);
    let [p0, p1, p2] = t[rng.below(4)];
    ray.t_max = match (rng.below(5), tri.intersect(f32::INFINITY, p0, p1, p2)) {
        (0, _) => f32::INFINITY,
        (1, Some((h, ..))) => h,
        (2, Some((h, ..))) => h.next_up(),
        (3, Some((h, ..))) => h.next_down(),
        (_, Some((h, ..))) => h * 2.0 * rng.f(),
        (_, None) => [0.0, -0.0, f32::MIN_POSITIVE, f32::MAX, 1.0, f32::NAN][rng.below(6)],
    };
    (t, ray)
}

/// The vector test's answer per lane, the scalar test filling in the fallback lanes.
fn lane_answers(t: &Tris, tri: &TriRay, t_max: f32, lanes: &Lanes) -> [Found; 4] {
    core::array::from_fn(|l| {
        if lanes.fallback & (1 << l) != 0 {
            let [p0, p1, p2] = t[l];
            tri.intersect(t_max, p0, p1, p2)
        } else if lanes.hit & (1 << l) != 0 {
            Some((lanes.t[l], lanes.b[0][l], lanes.b[1][l], lanes.b[2][l]))
        } else {
            None
        }
    })
}

/// Exact comparison: both miss, or both hit with the same bits of t and every barycentric.
fn same(a: Found, b: Found) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(x), Some(y)) => {
            x.0.to_bits() == y.0.to_bits()
                && x.1.to_bits() == y.1.to_bits()
                && x.2.to_bits() == y.2.to_bits()
                && x.3.to_bits() == y.3.to_bits()
        }
        _ => false,
    }
}

/// Bitwise equality of two four-lane results: the masks, and the values of the hit lanes (the
/// only ones the contract defines).
fn same_lanes(a: &Lanes, b: &Lanes) -> bool {
    let eq = |x: &[f32; 4], y: &[f32; 4]| {
        (0..4).all(|l| a.hit & (1 << l) == 0 || x[l].to_bits() == y[l].to_bits())
    };
    a.hit == b.hit
        && a.fallback == b.fallback
        && eq(&a.t, &b.t)
        && (0..3).all(|i| eq(&a.b[i], &b.b[i]))
        && eq(&a.t_scaled, &b.t_scaled)
        && eq(&a.det, &b.det)
}

const CASES: usize = 240_000;
const KINDS: usize = 7;

#[test]
fn four_lanes_equal_the_scalar_test_bit_for_bit() {
    let mut rng = Rng(2024);
    let mut hits = [0usize; KINDS];
    let mut fallbacks = [0usize; KINDS];
    let mut t_max_ties = 0;
    for i in 0..CASES {
        let kind = i % KINDS;
        let (t, ray) = case(&mut rng, kind);
        let tri = TriRay::new(&ray);
        let r4 = Ray4::new(&tri);
        let blk = block(&t);
        let lanes = test4(&blk, &r4, ray.t_max);
        // The SSE version (test4 on x86_64) and the portable one give the same bits.
        let portable = test4_scalar(&blk, &r4, ray.t_max);
        assert!(
            same_lanes(&lanes, &portable),
            "SSE and portable differ: {lanes:?} vs {portable:?} for {t:?} {ray:?}"
        );
        let got = lane_answers(&t, &tri, ray.t_max, &lanes);
        for l in 0..4 {
            let [p0, p1, p2] = t[l];
            let want = tri.intersect(ray.t_max, p0, p1, p2);
            assert!(
                same(got[l], want),
                "kind {kind} lane {l}: four-lane {:?} vs scalar {want:?} for {t:?} {ray:?}",
                got[l]
            );
            if want.is_some_and(|w| w.0.next_up() == ray.t_max || w.0 == ray.t_max) {
                t_max_ties += 1;
            }
        }
        hits[kind] += lanes.hit.count_ones() as usize;
        fallbacks[kind] += lanes.fallback.count_ones() as usize;
    }
    eprintln!("hit lanes per kind {hits:?}, fallback lanes {fallbacks:?}, t_max ties {t_max_ties}");
    // Every kind of case but the degenerate triangles (kind 3) produces vector hits, and the
    // exact-edge cases reach the fallback.
    assert!(
        hits.iter().enumerate().all(|(k, &h)| k == 3 || h > 300),
        "too few hits: {hits:?}"
    );
    assert!(fallbacks[1] > 1000 && fallbacks[2] > 1000, "{fallbacks:?}");
    assert!(
        t_max_ties > 1000,
        "t_max edge cases not reached ({t_max_ties})"
    );
}

/// Hits found with a larger `t_max`, re-checked against a smaller one as the leaf loop does,
/// agree with the scalar test run at the smaller one.
#[test]
fn rechecking_a_hit_with_a_smaller_t_max_equals_the_scalar_test() {
    let mut rng = Rng(77);
    let (mut checked, mut rejected) = (0, 0);
    for i in 0..CASES / 2 {
        let (t, mut ray) = case(&mut rng, [0, 1, 4, 6][i % 4]);
        ray.t_max = f32::INFINITY;
        let tri = TriRay::new(&ray);
        let lanes = test4(&block(&t), &Ray4::new(&tri), ray.t_max);
        for l in 0..4 {
            if lanes.hit & (1 << l) == 0 {
                continue;
            }
            let h = lanes.t[l];
            // t_max at, just above, just below the hit, and at another lane's hit.
            let other = lanes.t[rng.below(4)];
            for t_max in [h, h.next_up(), h.next_down(), other, h * 1.0000001] {
                let [p0, p1, p2] = t[l];
                let want = tri.intersect(t_max, p0, p1, p2);
                let got = lanes.accepts(l, t_max).then_some((
                    lanes.t[l],
                    lanes.b[0][l],
                    lanes.b[1][l],
                    lanes.b[2][l],
                ));
                assert!(
                    same(got, want),
                    "re-check {got:?} vs {want:?}: {t:?} {ray:?}"
                );
                checked += 1;
                rejected += usize::from(want.is_none());
            }
        }
    }
    assert!(
        checked > 50_000 && rejected > 20_000,
        "{checked} {rejected}"
    );
}

/// Controls: the comparison notices a single result moved by one ulp, and the case set notices
/// a formula that differs from the scalar test only in rounding (`t_scaled / det` instead of
/// `t_scaled * (1 / det)`).
#[test]
fn controls_one_ulp_changes_are_detected() {
    let mut rng = Rng(5);
    let (mut moved, mut formula) = (0, 0);
    for i in 0..CASES / 4 {
        let (t, ray) = case(&mut rng, [0, 4, 6][i % 3]);
        let tri = TriRay::new(&ray);
        let lanes = test4(&block(&t), &Ray4::new(&tri), ray.t_max);
        let got = lane_answers(&t, &tri, ray.t_max, &lanes);
        for (l, found) in got.iter().enumerate() {
            let Some((h, b0, b1, b2)) = *found else {
                continue;
            };
            // One ulp on t, then on each barycentric: every change is caught.
            let nudged = [
                (h.next_up(), b0, b1, b2),
                (h, b0.next_down(), b1, b2),
                (h, b0, b1.next_up(), b2),
                (h, b0, b1, b2.next_up()),
            ];
            for n in nudged {
                assert!(!same(Some(n), *found), "a 1-ulp change passed");
                moved += 1;
            }
            let mut wrong = lanes;
            wrong.t[l] = lanes.t_scaled[l] / lanes.det[l];
            if !same_lanes(&wrong, &lanes) {
                formula += 1;
            }
        }
    }
    assert!(moved > 10_000, "{moved}");
    // The alternative formula rounds differently in a good share of hits.
    assert!(
        formula > 1_000,
        "only {formula} hits tell t_scaled / det apart"
    );
}

/// The eight-lane test (`accel::tri_block_pair`: two blocks per AVX2 pass, where the CPU has AVX2)
/// gives the same masks and hit-lane bits as the two four-lane tests, block `a` in lanes 0-3 and
/// block `b` in lanes 4-7. Control: the blocks swapped are told apart.
#[test]
fn eight_lanes_equal_two_four_lane_tests_bit_for_bit() {
    let mut rng = Rng(808);
    let avx2 = Avx2::detect();
    eprintln!("AVX2: {}", avx2.is_some());
    let (mut hits, mut high_hits, mut fallbacks, mut swapped_differ) = (0, 0, 0, 0);
    for i in 0..CASES / 2 {
        let (ta, ray) = case(&mut rng, i % KINDS);
        // Block b: a's triangles in another lane order (so both halves hit) or another case's.
        let tb = if i % 2 == 0 {
            [ta[2], ta[0], ta[3], ta[1]]
        } else {
            case(&mut rng, (i / 2) % KINDS).0
        };
        let (a, b) = (block(&ta), block(&tb));
        let r4 = Ray4::new(&TriRay::new(&ray));
        let want = Lanes8::join(
            &test4_scalar(&a, &r4, ray.t_max),
            &test4_scalar(&b, &r4, ray.t_max),
        );
        let mut got = vec![test8_portable(&a, &b, &r4, ray.t_max)];
        got.push(Portable.tri8(&a, &b, &r4, ray.t_max));
        if let Some(t) = avx2 {
            got.push(t.tri8(&a, &b, &r4, ray.t_max));
            // Control: the same blocks in the other order are a different answer when the two
            // halves differ.
            let swapped = t.tri8(&b, &a, &r4, ray.t_max);
            if ta != tb && !swapped.same_bits(&want) {
                swapped_differ += 1;
            }
        }
        for g in &got {
            assert!(
                g.same_bits(&want),
                "eight-lane {g:?} vs four-lane pair {want:?} for {ta:?} {tb:?} {ray:?}"
            );
        }
        hits += want.hit.count_ones();
        high_hits += (want.hit >> 4).count_ones();
        fallbacks += want.fallback.count_ones();
    }
    eprintln!("hit lanes {hits} (block b: {high_hits}), fallback lanes {fallbacks}");
    assert!(high_hits > 10_000 && hits > high_hits + 10_000 && fallbacks > 1000);
    assert!(
        avx2.is_none() || swapped_differ > 10_000,
        "{swapped_differ}"
    );
}

//! Ray casts in the Cornell box, the benchmark scene Tessera trails Mitsuba 3 on: Tessera's own
//! casts (`Scene::intersect_hit`, `Scene::occluded`: cbox's hierarchy is one 8-wide node) against
//! Embree 3 one ray at a time (`rtcIntersect1`, `rtcOccluded1`) and in packets of 8 and 16 rays
//! (`rtcIntersect8/16`, `rtcOccluded8/16`), which is how Mitsuba 3's `llvm_ad_rgb` traces: it hands
//! Embree packets as wide as its vector registers (16 lanes with AVX-512). The question it
//! answers: how much of Mitsuba's lead in samples per second on cbox is in casting rays?
//!
//! Rays as the path loop casts them: from points where uniform random rays inside the box hit a
//! surface, a continuation ray (uniform over the hemisphere the hit was seen from, closest hit)
//! and a shadow segment to a uniform point on the light (any hit), both with Tessera's own ray
//! offsets; the packets take consecutive rays, so they are as incoherent as the path loop's.
//! The `px` rows are the first vertex of one pixel's samples instead (16 jittered camera rays of
//! a random pixel, then each hit's continuation ray and shadow segment), consecutive, so a
//! packet holds one pixel's samples, as it would in a renderer that packs them that way.
//! Embree one ray at a time also runs in its robust mode (`embreeR1`, `RTC_SCENE_FLAG_ROBUST`: a
//! watertight triangle test and conservative node tests, the guarantees Tessera's casts give).
//! Rays per second of one thread, best of 5 alternating rounds; the hit counts of all casts must
//! agree (it panics otherwise).
//!
//! `cargo bench -p tessera-benches --features embree --bench embree_small [-- SCENE.xml]`
//! (default `scenes/cbox.xml`; any scene of triangles only). Needs Embree 3
//! (`scripts/install_embree.sh`).
mod embree_ffi;

use embree_ffi::{Embree, Mode};
use glam::{Vec2, Vec3};
use std::path::Path;
use std::time::Instant;
use tessera::scene::load_scene;
use tessera_benches::Rng;
use tessera_core::emitter::Emitter;
use tessera_core::geometry::{Interaction, Prim};
use tessera_core::math::Ray;
use tessera_core::scene::Scene;

/// Rays cast per second by `cast`, which takes a chunk of rays and returns how many hit: best of
/// `rounds` rounds of at least 0.2 s each; also the hit count of one pass.
fn rate(
    rays: &[Ray],
    chunk: usize,
    rounds: usize,
    mut cast: impl FnMut(&[Ray]) -> usize,
) -> (f64, usize) {
    let hits: usize = rays.chunks(chunk).map(&mut cast).sum();
    let mut best = 0.0f64;
    for _ in 0..rounds {
        let start = Instant::now();
        let mut passes = 0usize;
        let mut found = 0usize;
        while passes == 0 || start.elapsed().as_secs_f64() < 0.2 {
            for c in rays.chunks(chunk) {
                found += cast(std::hint::black_box(c));
            }
            passes += 1;
        }
        std::hint::black_box(found);
        best = best.max((passes * rays.len()) as f64 / start.elapsed().as_secs_f64());
    }
    (best, hits)
}

/// A scene's triangles for Embree: positions (three per triangle, unshared) and indices; and
/// the corners of the light's triangles.
struct Triangles {
    positions: Vec<[f32; 3]>,
    indices: Vec<[u32; 3]>,
    light: Vec<[Vec3; 3]>,
}

/// The scene's triangles, in primitive order.
fn triangles(scene: &Scene) -> Triangles {
    let light_shape = scene.emitters.iter().find_map(|e| match e {
        Emitter::Area(a) => Some(a.shape),
        _ => None,
    });
    let (mut pos, mut idx, mut light) = (vec![], vec![], vec![]);
    for (i, p) in scene.prims.iter().enumerate() {
        let Prim::Triangle { shape, .. } = p else {
            panic!("a primitive that is not a triangle: this bench takes triangle scenes only");
        };
        let c = scene.triangle(i).expect("a triangle");
        let n = pos.len() as u32;
        pos.extend(c.map(|v| v.to_array()));
        idx.push([n, n + 1, n + 2]);
        if Some(*shape) == light_shape {
            light.push(c);
        }
    }
    Triangles {
        positions: pos,
        indices: idx,
        light,
    }
}

/// The rays a path vertex at `si` casts: a continuation ray, uniform over the hemisphere `si` was
/// seen from, and a shadow segment to a uniform point on a uniformly chosen light triangle.
fn vertex_rays(si: &Interaction, light: &[[Vec3; 3]], rng: &mut Rng) -> (Ray, Ray) {
    let side = si.ng.dot(si.wi).signum();
    let d = rng.dir();
    let bounce = si.spawn_ray(if d.dot(si.ng) * side < 0.0 { -d } else { d });
    let [a, e1, e2] = light[(rng.f() * light.len() as f32) as usize % light.len()];
    let (mut u, mut v) = (rng.f(), rng.f());
    if u + v > 1.0 {
        (u, v) = (1.0 - u, 1.0 - v);
    }
    (bounce, si.spawn_ray_to(a + (e1 - a) * u + (e2 - a) * v))
}

fn main() {
    let arg = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let path = arg.map_or_else(|| root.join("scenes/cbox.xml"), Into::into);
    let scene = load_scene(&path, &[])
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    let Triangles {
        positions: pos,
        indices: idx,
        light,
    } = triangles(&scene);
    assert!(!light.is_empty(), "the scene needs a triangle area light");
    let embree = Embree::new(&pos, &idx);
    let robust = Embree::with_mode(&pos, &idx, Mode::Robust);
    let b = scene.bounds();
    let (lo, size) = (b.min, b.max - b.min);
    let mut rng = Rng(11);
    let (mut bounce, mut shadow) = (vec![], vec![]);
    while bounce.len() < 1 << 16 {
        let o = lo + size * Vec3::new(rng.f(), rng.f(), rng.f()) * 0.98 + size * 0.01;
        let Some(si) = scene.intersect(&Ray::new(o, rng.dir())) else {
            continue;
        };
        let (b, s) = vertex_rays(&si, &light, &mut rng);
        bounce.push(b);
        shadow.push(s);
    }
    // A pixel's samples at the first vertex, as a renderer whose packets hold one pixel's
    // samples casts them: 16 jittered camera rays of one pixel (pixels in random order), and from
    // each one's hit a continuation ray and a shadow segment as above.
    let (mut camera_px, mut bounce_px, mut shadow_px) = (vec![], vec![], vec![]);
    let (w, h) = (scene.camera.width, scene.camera.height);
    while camera_px.len() < 1 << 16 {
        let px = Vec2::new(
            (rng.f() * w as f32).floor().min(w as f32 - 1.0),
            (rng.f() * h as f32).floor().min(h as f32 - 1.0),
        );
        let group: Vec<Ray> = (0..16)
            .map(|_| scene.camera.generate_ray(px + Vec2::new(rng.f(), rng.f())))
            .collect();
        let hits: Vec<_> = group.iter().filter_map(|r| scene.intersect(r)).collect();
        if hits.len() < group.len() {
            continue;
        }
        for (r, si) in group.into_iter().zip(hits) {
            camera_px.push(r);
            let (b, s) = vertex_rays(&si, &light, &mut rng);
            bounce_px.push(b);
            shadow_px.push(s);
        }
    }
    println!(
        "{}: {} triangles, {} rays of each kind; M rays/s, one thread, best of 5",
        path.display(),
        idx.len(),
        bounce.len()
    );
    println!(
        "{:>10} {:>9} {:>9} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8} {:>8}",
        "rays",
        "tessera",
        "embree1",
        "embree8",
        "embree16",
        "embreeR1",
        "t/e1",
        "t/e8",
        "t/e16",
        "t/eR1"
    );
    for (kind, rays, any) in [
        ("bounce", &bounce, false),
        ("shadow", &shadow, true),
        ("camera px", &camera_px, false),
        ("bounce px", &bounce_px, false),
        ("shadow px", &shadow_px, true),
    ] {
        let mut best = [0.0f64; 5];
        let mut hits = [0usize; 5];
        for _ in 0..5 {
            let r = if any {
                [
                    rate(rays, 1, 1, |c| usize::from(scene.occluded(&c[0]))),
                    rate(rays, 1, 1, |c| usize::from(embree.occluded(&c[0]))),
                    rate(rays, 8, 1, |c| embree.occluded8(c)),
                    rate(rays, 16, 1, |c| embree.occluded16(c)),
                    rate(rays, 1, 1, |c| usize::from(robust.occluded(&c[0]))),
                ]
            } else {
                [
                    rate(rays, 1, 1, |c| {
                        usize::from(scene.intersect_hit(&c[0]).is_some())
                    }),
                    rate(rays, 1, 1, |c| {
                        usize::from(embree.intersect(&c[0]).is_some())
                    }),
                    rate(rays, 8, 1, |c| embree.intersect8(c)),
                    rate(rays, 16, 1, |c| embree.intersect16(c)),
                    rate(rays, 1, 1, |c| {
                        usize::from(robust.intersect(&c[0]).is_some())
                    }),
                ]
            };
            for (k, (s, h)) in r.into_iter().enumerate() {
                best[k] = best[k].max(s);
                hits[k] = h;
            }
        }
        // Rays grazing an edge may be decided differently (Tessera's test is watertight):
        // allow a few in a thousand, no more.
        for (k, h) in hits.iter().enumerate() {
            let diff = h.abs_diff(hits[0]);
            assert!(
                diff * 1000 <= rays.len() * 2,
                "{kind}: cast {k} found {h} hits, Tessera {}",
                hits[0]
            );
        }
        println!(
            "{kind:>10} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>8.2} {:>8.2} {:>8.2} {:>8.2}   \
             hits {:?}",
            best[0] / 1e6,
            best[1] / 1e6,
            best[2] / 1e6,
            best[3] / 1e6,
            best[4] / 1e6,
            best[0] / best[1],
            best[0] / best[2],
            best[0] / best[3],
            best[0] / best[4],
            hits
        );
    }
}

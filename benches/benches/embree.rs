//! Tessera's ray casts with its 8-wide BVH, collapsed from the binary SAH tree greedily (`g8`,
//! the first collapse) and with the default surface-area collapse (`bvh8`; `BVH8_COLLAPSE`
//! overrides it, see `tessera_benches::collapse`), both with the scene's leaf code (blocks of
//! four triangles), against Embree 3's single-ray queries (`rtcIntersect1`, `rtcOccluded1`) on
//! the same meshes and rays, in the same run: rays per CPU-second, best of 5 alternating rounds,
//! one thread; also the build time of each (Tessera's: SAH build, collapse and block packing;
//! Embree with `threads=1`), bytes per triangle, and how often all four agree on hit or miss.
//! Embree runs twice: in its default mode (`emb`: its fastest triangle test, which is not
//! watertight) and with `RTC_SCENE_FLAG_ROBUST` (`embR`: a watertight test and conservative node
//! tests, the guarantees Tessera's casts always give), so `8/emb` is the ratio to Embree at its
//! fastest and `8/embR` the like-for-like one.
//!
//! Optional: needs Embree 3 (`scripts/install_embree.sh`), so it is built only with the feature:
//! `cargo bench -p tessera-benches --features embree --bench embree` (sizes as arguments, e.g.
//! `-- 1k 100k`). Tessera itself never links Embree; the FFI is in `embree_ffi/`.
// The packet queries in it are `embree_small`'s.
#[allow(dead_code)]
mod embree_ffi;

use embree_ffi::{Embree, Mode};
use std::time::Instant;
use tessera_benches::{
    build_params, bumpy_sphere, camera_rays, frequency_for, mesh_parts, random_rays,
    rays_per_second, wanted_sizes, Bvh8Greedy, WideScene,
};
use tessera_core::accel::Bvh8;
use tessera_core::scene::Scene;

/// Children per node.
fn fill(b: &Bvh8) -> f64 {
    let used: u32 = b.nodes.iter().map(|n| n.used.count_ones()).sum();
    f64::from(used) / b.nodes.len().max(1) as f64
}

fn main() {
    let camera = camera_rays(256);
    let random = random_rays(1 << 16, 7);
    println!(
        "{:>5} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>6} {:>6} {:>6} {:>7}",
        "mesh",
        "tris",
        "g8 build",
        "b8 build",
        "eb build",
        "ebR build",
        "g8 Mr/s",
        "bvh8 Mr/s",
        "emb Mr/s",
        "embR Mr/s",
        "g8/emb",
        "8/emb",
        "8/embR",
        "agree"
    );
    // `CAST_ONLY=bvh8|g8|embree|robust|none` (for callgrind and perf): `CAST_PASSES` (default 1)
    // passes of the random rays, closest hit, with one of them on the first size, then exit
    // (`embree` is its default mode, `robust` its robust mode, the one the table's `embR` is).
    let only = std::env::var("CAST_ONLY").ok();
    for (label, target) in wanted_sizes() {
        let (positions, indices) = bumpy_sphere(frequency_for(target));
        if let Some(which) = &only {
            let pos: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
            let embree = match which.as_str() {
                "robust" => Embree::with_mode(&pos, &indices, Mode::Robust),
                _ => Embree::new(&pos, &indices),
            };
            let scene = Scene::with_build_params(mesh_parts(positions, indices), build_params())
                .expect("valid scene");
            let w8 = WideScene::<Bvh8>::new(&scene, build_params());
            let g8 = WideScene::<Bvh8Greedy>::new(&scene, build_params());
            let passes: usize =
                std::env::var("CAST_PASSES").map_or(1, |p| p.parse().expect("passes"));
            let found = std::iter::repeat_n(random.iter(), passes)
                .flatten()
                .filter(|r| match which.as_str() {
                    "embree" | "robust" => embree.intersect(r).is_some(),
                    "none" => false,
                    "g8" => g8.intersect_hit(r).is_some(),
                    _ => w8.intersect_hit(r).is_some(),
                })
                .count();
            println!("{which}: {found} of {} rays hit", random.len());
            return;
        }
        let pos: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
        let start = Instant::now();
        let embree = Embree::new(&pos, &indices);
        let eb = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let robust = Embree::with_mode(&pos, &indices, Mode::Robust);
        let ebr = start.elapsed().as_secs_f64();
        let parts = mesh_parts(positions, indices);
        let scene = Scene::with_build_params(parts, build_params()).expect("valid scene");
        let start = Instant::now();
        let g8w = WideScene::<Bvh8Greedy>::new(&scene, build_params());
        let bg = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let w8 = WideScene::<Bvh8>::new(&scene, build_params());
        let b8 = start.elapsed().as_secs_f64();
        let tris = scene.prims.len();
        let ((ng, tg), (n8, t8)) = (g8w.bytes_per_triangle(), w8.bytes_per_triangle());
        println!(
            "{label:>5}: bytes/triangle: greedy {ng:.1} + {tg:.1} = {:.1}, bvh8 {n8:.1} + {t8:.1} = \
             {:.1} (nodes + blocks); depth greedy {} bvh8 {}; children per node greedy {:.2} \
             bvh8 {:.2}; avx2 {}",
            ng + tg,
            n8 + t8,
            g8w.bvh.0.depth(),
            w8.bvh.depth(),
            fill(&g8w.bvh.0),
            fill(&w8.bvh),
            w8.bvh.uses_avx2()
        );
        for (kind, rays) in [("camera", &camera), ("random", &random)] {
            for any in [false, true] {
                let (mut rg, mut r8, mut e, mut er) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
                for _ in 0..5 {
                    if any {
                        rg = rg.max(rays_per_second(rays, 1, |r| g8w.occluded(r)));
                        r8 = r8.max(rays_per_second(rays, 1, |r| w8.occluded(r)));
                        e = e.max(rays_per_second(rays, 1, |r| embree.occluded(r)));
                        er = er.max(rays_per_second(rays, 1, |r| robust.occluded(r)));
                    } else {
                        rg = rg.max(rays_per_second(rays, 1, |r| g8w.intersect_hit(r).is_some()));
                        r8 = r8.max(rays_per_second(rays, 1, |r| w8.intersect_hit(r).is_some()));
                        e = e.max(rays_per_second(rays, 1, |r| embree.intersect(r).is_some()));
                        er = er.max(rays_per_second(rays, 1, |r| robust.intersect(r).is_some()));
                    }
                }
                let agree = rays
                    .iter()
                    .filter(|r| {
                        let o = embree.occluded(r);
                        g8w.occluded(r) == o && w8.occluded(r) == o && robust.occluded(r) == o
                    })
                    .count() as f64
                    / rays.len() as f64;
                println!(
                    "{label:>5} {tris:>8} {:>6.1} ms {:>6.1} ms {:>6.1} ms {:>6.1} ms {:>9.2} {:>9.2} \
                     {:>9.2} {:>9.2} {:>6.2} {:>6.2} {:>6.2} {:>6.2}%  {kind} {}",
                    bg * 1e3,
                    b8 * 1e3,
                    eb * 1e3,
                    ebr * 1e3,
                    rg / 1e6,
                    r8 / 1e6,
                    e / 1e6,
                    er / 1e6,
                    rg / e,
                    r8 / e,
                    r8 / er,
                    agree * 100.0,
                    if any { "any" } else { "closest" }
                );
            }
        }
    }
}

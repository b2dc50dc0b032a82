//! The scene's 8-wide BVH (its casts, `Scene::intersect_hit` and `Scene::occluded`) against the
//! binary BVH it is collapsed from, traversed as scenes did before the wide BVHs
//! (`tessera_benches::BinaryScene`), in the same run: rays per second (best of 5 alternating
//! rounds) for coherent camera rays and incoherent random rays, closest and any hit, on bumpy
//! spheres of about 10^3 to 10^6 triangles, the ratio, and build time against triangle count;
//! and per ray the nodes visited, leaves reached and triangle blocks tested. The Embree bench
//! compares the 8-wide BVH with Embree.
//!
//! `cargo bench -p tessera-benches --bench bvh_compare` (all sizes) or with sizes as arguments,
//! e.g. `cargo bench -p tessera-benches --bench bvh_compare -- 1k 100k`;
//! `BVH_PARAMS=max_leaf,traversal_cost,block` builds with other SAH parameters.
use std::time::Instant;
use tessera_benches::{
    build_params, bumpy_sphere, bytes_per_triangle, camera_rays, frequency_for, mesh_parts,
    random_rays, rays_per_second, thread_cpu_seconds, wanted_sizes, BinaryScene,
};
use tessera_core::accel::TraversalCounts;
use tessera_core::scene::Scene;

const ROUNDS: usize = 5;
fn main() {
    let camera = camera_rays(256);
    let random = random_rays(1 << 16, 7);
    println!(
        "{:>5} {:>8} {:>10} {:>7} {:>12} {:>12} {:>6}",
        "mesh", "tris", "build ms", "ns/tri", "binary Mr/s", "bvh8 Mr/s", "ratio"
    );
    for (label, target) in wanted_sizes() {
        let (p, i) = bumpy_sphere(frequency_for(target));
        let parts = mesh_parts(p, i);
        let params = build_params();
        // Build time per build in this thread's CPU time where available (the build is
        // single-threaded), repeated to at least 0.3 s as that clock ticks coarsely.
        let (wall, cpu) = (Instant::now(), thread_cpu_seconds());
        let mut builds = 0;
        let (scene, build) = loop {
            let scene = Scene::with_build_params(parts.clone(), params).expect("valid scene");
            builds += 1;
            let spent = match (cpu, thread_cpu_seconds()) {
                (Some(a), Some(b)) => b - a,
                _ => wall.elapsed().as_secs_f64(),
            };
            if spent >= 0.3 {
                break (scene, spent / builds as f64);
            }
        };
        let tris = scene.prims.len();
        let bin = BinaryScene::new(&scene);
        let n = tris as f64;
        let (nodes, corners, ids) = bytes_per_triangle(&scene);
        println!(
            "{label:>5}: bytes/triangle: bvh8 nodes {nodes:.1} ({} nodes, {:.2} children each, depth {}) + triangle blocks \
             {corners:.1} = {:.1} (+ primitive ids {ids:.1}); binary: nodes {:.1} + triangles \
             {:.1}",
            scene.bvh.nodes.len(),
            scene
                .bvh
                .nodes
                .iter()
                .map(|n| n.used.count_ones())
                .sum::<u32>() as f64
                / scene.bvh.nodes.len() as f64,
            scene.bvh.depth(),
            nodes + corners,
            bin.bvh.memory_bytes() as f64 / n,
            std::mem::size_of_val(bin.tris.as_slice()) as f64 / n,
        );
        for (kind, rays) in [("camera", &camera), ("random", &random)] {
            for any in [false, true] {
                let mut c = TraversalCounts::default();
                for r in rays.iter() {
                    if any {
                        scene.occluded_counted(r, &mut c);
                    } else {
                        scene.intersect_hit_counted(r, &mut c);
                    }
                }
                let per = |x: u64| x as f64 / c.rays as f64;
                println!(
                    "{label:>5}: per {kind} {} ray: {:.1} nodes, {:.1} leaves, {:.1} blocks",
                    if any { "any" } else { "closest" },
                    per(c.nodes),
                    per(c.leaves),
                    per(c.blocks)
                );
            }
        }
        for (kind, rays) in [("camera", &camera), ("random", &random)] {
            for any in [false, true] {
                // Alternate the two so both see the same machine load; keep the best round.
                let (mut b, mut w) = (0.0f64, 0.0f64);
                for _ in 0..ROUNDS {
                    if any {
                        b = b.max(rays_per_second(rays, 1, |r| bin.occluded(r)));
                        w = w.max(rays_per_second(rays, 1, |r| scene.occluded(r)));
                    } else {
                        b = b.max(rays_per_second(rays, 1, |r| bin.intersect_hit(r).is_some()));
                        w = w.max(rays_per_second(rays, 1, |r| {
                            scene.intersect_hit(r).is_some()
                        }));
                    }
                }
                println!(
                    "{label:>5} {tris:>8} {:>10.1} {:>7.0} {:>12.2} {:>12.2} {:>6.2}  {kind} {}",
                    build * 1e3,
                    build * 1e9 / tris as f64,
                    b / 1e6,
                    w / 1e6,
                    w / b,
                    if any { "any" } else { "closest" }
                );
            }
        }
    }
}

//! The 4-wide BVH against the binary one in the same run: rays per second (best of 3 rounds)
//! for coherent camera rays and incoherent random rays, closest and any hit, on bumpy spheres
//! of about 10^3 to 10^6 triangles, the ratio, and build time against triangle count.
//!
//! `cargo bench -p tessera-benches --bench bvh_compare` (all sizes) or with sizes as arguments,
//! e.g. `cargo bench -p tessera-benches --bench bvh_compare -- 1k 100k`.
use std::time::Instant;
use tessera_benches::{
    bumpy_sphere, camera_rays, frequency_for, mesh_parts, random_rays, rays_per_second, BinaryScene,
};
use tessera_core::scene::Scene;

const SIZES: [(&str, usize); 4] = [
    ("1k", 1_000),
    ("10k", 10_000),
    ("100k", 100_000),
    ("1M", 1_000_000),
];

fn main() {
    let wanted: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let camera = camera_rays(256);
    let random = random_rays(1 << 16, 7);
    println!(
        "{:>5} {:>8} {:>10} {:>7} {:>12} {:>12} {:>6}",
        "mesh", "tris", "build ms", "ns/tri", "binary Mr/s", "bvh4 Mr/s", "ratio"
    );
    for (label, target) in SIZES {
        if !wanted.is_empty() && !wanted.iter().any(|w| w == label) {
            continue;
        }
        let (p, i) = bumpy_sphere(frequency_for(target));
        let parts = mesh_parts(p, i);
        let start = Instant::now();
        let scene = Scene::new(parts).expect("valid scene");
        let build = start.elapsed().as_secs_f64();
        let tris = scene.prims.len();
        let bin = BinaryScene::new(&scene);
        for (kind, rays) in [("camera", &camera), ("random", &random)] {
            for any in [false, true] {
                let (b, w) = if any {
                    (
                        rays_per_second(rays, 3, |r| bin.occluded(r)),
                        rays_per_second(rays, 3, |r| scene.occluded(r)),
                    )
                } else {
                    (
                        rays_per_second(rays, 3, |r| bin.intersect_hit(r).is_some()),
                        rays_per_second(rays, 3, |r| scene.intersect_hit(r).is_some()),
                    )
                };
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

//! BVH build (triangles per second) and ray casts (rays per second: coherent camera rays and
//! incoherent random rays, closest hit and any hit; the scene's 8-wide BVH and, as `binary_*`,
//! the binary BVH it is collapsed from) on bumpy geodesic spheres of about 10^3 to 10^6
//! triangles. Prints the acceleration structure's bytes per triangle first.
//!
//! `cargo bench -p tessera-benches --bench accel` (all sizes), or a filter such as
//! `cargo bench -p tessera-benches --bench accel -- 100k`.
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use tessera_benches::{
    bumpy_sphere, bytes_per_triangle, camera_rays, frequency_for, geodesic_triangles, mesh_parts,
    random_rays, BinaryScene, MESH_SIZES,
};
use tessera_core::scene::Scene;

const RAYS: usize = 1 << 16;

fn accel(c: &mut Criterion) {
    let camera = camera_rays(256);
    let random = random_rays(RAYS, 7);
    for (label, target) in MESH_SIZES {
        let n = frequency_for(target);
        let (positions, indices) = bumpy_sphere(n);
        let parts = mesh_parts(positions, indices);
        let tris = geodesic_triangles(n);
        let scene = Scene::new(parts.clone()).expect("valid scene");
        assert_eq!(scene.prims.len(), tris);
        let (nodes, corners, prims) = bytes_per_triangle(&scene);
        let hits = camera
            .iter()
            .filter(|r| scene.intersect_hit(r).is_some())
            .count();
        println!(
            "mesh {label}: {tris} triangles, {} BVH8 nodes; bytes/triangle: {nodes:.1} nodes + \
             {corners:.1} triangle blocks = {:.1} (+ {prims:.1} primitive ids); camera rays \
             hitting: {:.0}%",
            scene.bvh.nodes.len(),
            nodes + corners,
            100.0 * hits as f64 / camera.len() as f64
        );

        let big = tris > 200_000;
        let mut g = c.benchmark_group(format!("bvh_build/{label}"));
        g.sample_size(10)
            .warm_up_time(Duration::from_secs(1))
            .measurement_time(Duration::from_secs(if big { 8 } else { 3 }));
        g.throughput(Throughput::Elements(tris as u64));
        g.bench_function("scene_new", |b| {
            b.iter_batched(
                || parts.clone(),
                |p| Scene::new(p).expect("valid scene"),
                BatchSize::LargeInput,
            )
        });
        g.finish();

        let bin = BinaryScene::new(&scene);
        let mut g = c.benchmark_group(format!("rays/{label}"));
        g.sample_size(10)
            .warm_up_time(Duration::from_secs(1))
            .measurement_time(Duration::from_secs(2));
        for (kind, rays) in [("camera", &camera), ("random", &random)] {
            g.throughput(Throughput::Elements(rays.len() as u64));
            g.bench_function(format!("{kind}_closest"), |b| {
                b.iter(|| {
                    let mut found = 0u32;
                    for r in rays.iter() {
                        found += u32::from(scene.intersect_hit(black_box(r)).is_some());
                    }
                    found
                })
            });
            g.bench_function(format!("{kind}_any"), |b| {
                b.iter(|| {
                    let mut found = 0u32;
                    for r in rays.iter() {
                        found += u32::from(scene.occluded(black_box(r)));
                    }
                    found
                })
            });
            g.bench_function(format!("binary_{kind}_closest"), |b| {
                b.iter(|| {
                    let mut found = 0u32;
                    for r in rays.iter() {
                        found += u32::from(bin.intersect_hit(black_box(r)).is_some());
                    }
                    found
                })
            });
            g.bench_function(format!("binary_{kind}_any"), |b| {
                b.iter(|| {
                    let mut found = 0u32;
                    for r in rays.iter() {
                        found += u32::from(bin.occluded(black_box(r)));
                    }
                    found
                })
            });
        }
        g.finish();
    }
}

criterion_group!(benches, accel);
criterion_main!(benches);

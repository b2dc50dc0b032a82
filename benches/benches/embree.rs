//! Tessera's ray casts with its 8-wide BVH, collapsed from the binary SAH tree greedily (`g8`,
//! the first collapse) and with the default surface-area collapse (`bvh8`; `BVH8_COLLAPSE`
//! overrides it, see `tessera_benches::collapse`), both with the scene's leaf code (blocks of
//! four triangles), against Embree 3's single-ray queries (`rtcIntersect1`, `rtcOccluded1`) on
//! the same meshes and rays, in the same run: rays per CPU-second, best of 5 alternating rounds,
//! one thread; also the build time of each (Tessera's: SAH build, collapse and block packing;
//! Embree with `threads=1`), bytes per triangle, and how often all three agree on hit or miss.
//!
//! Optional: needs Embree 3 (`scripts/install_embree.sh`), so it is built only with the feature:
//! `cargo bench -p tessera-benches --features embree --bench embree` (sizes as arguments, e.g.
//! `-- 1k 100k`). Tessera itself never links Embree. The FFI below declares only the few calls
//! used, with the structs of `embree3/rtcore_ray.h` and `rtcore_common.h` (3.13, built with
//! `RTC_MAX_INSTANCE_LEVEL_COUNT 1` and `RTC_MIN_WIDTH 0` as Debian's is).
#![allow(unsafe_code)]
use std::ffi::{c_char, c_void};
use std::time::Instant;
use tessera_benches::{
    build_params, bumpy_sphere, camera_rays, frequency_for, mesh_parts, random_rays,
    rays_per_second, wanted_sizes, Bvh8Greedy, WideScene,
};
use tessera_core::accel::Bvh8;
use tessera_core::math::Ray;
use tessera_core::scene::Scene;

#[repr(C)]
struct RtcIntersectContext {
    flags: u32,
    filter: Option<extern "C" fn(*const c_void)>,
    inst_id: [u32; 1],
}

#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct RtcRay {
    org: [f32; 3],
    tnear: f32,
    dir: [f32; 3],
    time: f32,
    tfar: f32,
    mask: u32,
    id: u32,
    flags: u32,
}

#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct RtcHit {
    ng: [f32; 3],
    u: f32,
    v: f32,
    prim_id: u32,
    geom_id: u32,
    inst_id: [u32; 1],
}

#[repr(C)]
#[derive(Clone, Copy)]
struct RtcRayHit {
    ray: RtcRay,
    hit: RtcHit,
}

const INVALID_ID: u32 = u32::MAX;
const GEOMETRY_TYPE_TRIANGLE: u32 = 0;
const BUFFER_TYPE_INDEX: u32 = 0;
const BUFFER_TYPE_VERTEX: u32 = 1;
const FORMAT_UINT3: u32 = 0x5003;
const FORMAT_FLOAT3: u32 = 0x9003;

#[link(name = "embree3")]
extern "C" {
    fn rtcNewDevice(config: *const c_char) -> *mut c_void;
    fn rtcReleaseDevice(device: *mut c_void);
    fn rtcGetDeviceError(device: *mut c_void) -> u32;
    fn rtcNewScene(device: *mut c_void) -> *mut c_void;
    fn rtcReleaseScene(scene: *mut c_void);
    fn rtcNewGeometry(device: *mut c_void, kind: u32) -> *mut c_void;
    fn rtcSetSharedGeometryBuffer(
        geometry: *mut c_void,
        kind: u32,
        slot: u32,
        format: u32,
        ptr: *const c_void,
        byte_offset: usize,
        byte_stride: usize,
        item_count: usize,
    );
    fn rtcCommitGeometry(geometry: *mut c_void);
    fn rtcAttachGeometry(scene: *mut c_void, geometry: *mut c_void) -> u32;
    fn rtcReleaseGeometry(geometry: *mut c_void);
    fn rtcCommitScene(scene: *mut c_void);
    fn rtcIntersect1(scene: *mut c_void, ctx: *mut RtcIntersectContext, rayhit: *mut RtcRayHit);
    fn rtcOccluded1(scene: *mut c_void, ctx: *mut RtcIntersectContext, ray: *mut RtcRay);
}

/// An Embree device and scene over one triangle mesh whose buffers it shares (kept alive here).
struct Embree {
    device: *mut c_void,
    scene: *mut c_void,
    _vertices: Vec<f32>,
    _indices: Vec<u32>,
}

impl Embree {
    fn new(positions: &[[f32; 3]], indices: &[[u32; 3]]) -> Embree {
        // Embree reads vertex buffers 16 bytes at a time: one float of padding at the end.
        let mut vertices: Vec<f32> = positions.iter().flatten().copied().collect();
        vertices.push(0.0);
        let idx: Vec<u32> = indices.iter().flatten().copied().collect();
        // SAFETY: the config is a NUL-terminated string; every handle passed on is the non-null
        // one Embree returned (checked); the shared buffers point into `vertices` and `idx`, whose
        // heap storage lives (unmoved) in the returned struct as long as the scene.
        unsafe {
            let device = rtcNewDevice(c"threads=1".as_ptr());
            assert!(!device.is_null(), "rtcNewDevice failed");
            let scene = rtcNewScene(device);
            let geom = rtcNewGeometry(device, GEOMETRY_TYPE_TRIANGLE);
            assert!(
                !scene.is_null() && !geom.is_null(),
                "Embree scene or geometry"
            );
            rtcSetSharedGeometryBuffer(
                geom,
                BUFFER_TYPE_VERTEX,
                0,
                FORMAT_FLOAT3,
                vertices.as_ptr().cast(),
                0,
                12,
                positions.len(),
            );
            rtcSetSharedGeometryBuffer(
                geom,
                BUFFER_TYPE_INDEX,
                0,
                FORMAT_UINT3,
                idx.as_ptr().cast(),
                0,
                12,
                indices.len(),
            );
            rtcCommitGeometry(geom);
            rtcAttachGeometry(scene, geom);
            rtcReleaseGeometry(geom);
            rtcCommitScene(scene);
            assert_eq!(rtcGetDeviceError(device), 0, "Embree error");
            Embree {
                device,
                scene,
                _vertices: vertices,
                _indices: idx,
            }
        }
    }

    fn ray(r: &Ray) -> RtcRay {
        RtcRay {
            org: r.o.to_array(),
            tnear: 0.0,
            dir: r.d.to_array(),
            time: 0.0,
            tfar: r.t_max,
            mask: u32::MAX,
            id: 0,
            flags: 0,
        }
    }

    fn context() -> RtcIntersectContext {
        // As `rtcInitIntersectContext` (an inline function in the header).
        RtcIntersectContext {
            flags: 0,
            filter: None,
            inst_id: [INVALID_ID],
        }
    }

    /// Closest hit: `(t, primitive)`.
    fn intersect(&self, r: &Ray) -> Option<(f32, u32)> {
        let mut rh = RtcRayHit {
            ray: Self::ray(r),
            hit: RtcHit {
                ng: [0.0; 3],
                u: 0.0,
                v: 0.0,
                prim_id: INVALID_ID,
                geom_id: INVALID_ID,
                inst_id: [INVALID_ID],
            },
        };
        let mut ctx = Self::context();
        // SAFETY: `self.scene` is a committed scene; `ctx` and `rh` are valid, aligned locals.
        unsafe { rtcIntersect1(self.scene, &mut ctx, &mut rh) };
        (rh.hit.geom_id != INVALID_ID).then_some((rh.ray.tfar, rh.hit.prim_id))
    }

    fn occluded(&self, r: &Ray) -> bool {
        let mut ray = Self::ray(r);
        let mut ctx = Self::context();
        // SAFETY: as in `intersect`.
        unsafe { rtcOccluded1(self.scene, &mut ctx, &mut ray) };
        ray.tfar == f32::NEG_INFINITY
    }
}

impl Drop for Embree {
    fn drop(&mut self) {
        // SAFETY: the handles came from Embree and are released once.
        unsafe {
            rtcReleaseScene(self.scene);
            rtcReleaseDevice(self.device);
        }
    }
}

/// Children per node.
fn fill(b: &Bvh8) -> f64 {
    let used: u32 = b.nodes.iter().map(|n| n.used.count_ones()).sum();
    f64::from(used) / b.nodes.len().max(1) as f64
}

fn main() {
    let camera = camera_rays(256);
    let random = random_rays(1 << 16, 7);
    println!(
        "{:>5} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>6} {:>6} {:>7}",
        "mesh",
        "tris",
        "g8 build",
        "b8 build",
        "eb build",
        "g8 Mr/s",
        "bvh8 Mr/s",
        "emb Mr/s",
        "g8/emb",
        "8/emb",
        "agree"
    );
    // `CAST_ONLY=bvh8|g8|embree|none` (for callgrind and perf): `CAST_PASSES` (default 1) passes of
    // the random rays, closest hit, with one of the two on the first size, then exit.
    let only = std::env::var("CAST_ONLY").ok();
    for (label, target) in wanted_sizes() {
        let (positions, indices) = bumpy_sphere(frequency_for(target));
        if let Some(which) = &only {
            let pos: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
            let embree = Embree::new(&pos, &indices);
            let scene = Scene::with_build_params(mesh_parts(positions, indices), build_params())
                .expect("valid scene");
            let w8 = WideScene::<Bvh8>::new(&scene, build_params());
            let g8 = WideScene::<Bvh8Greedy>::new(&scene, build_params());
            let passes: usize =
                std::env::var("CAST_PASSES").map_or(1, |p| p.parse().expect("passes"));
            let found = std::iter::repeat_n(random.iter(), passes)
                .flatten()
                .filter(|r| match which.as_str() {
                    "embree" => embree.intersect(r).is_some(),
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
                let (mut rg, mut r8, mut e) = (0.0f64, 0.0f64, 0.0f64);
                for _ in 0..5 {
                    if any {
                        rg = rg.max(rays_per_second(rays, 1, |r| g8w.occluded(r)));
                        r8 = r8.max(rays_per_second(rays, 1, |r| w8.occluded(r)));
                        e = e.max(rays_per_second(rays, 1, |r| embree.occluded(r)));
                    } else {
                        rg = rg.max(rays_per_second(rays, 1, |r| g8w.intersect_hit(r).is_some()));
                        r8 = r8.max(rays_per_second(rays, 1, |r| w8.intersect_hit(r).is_some()));
                        e = e.max(rays_per_second(rays, 1, |r| embree.intersect(r).is_some()));
                    }
                }
                let agree = rays
                    .iter()
                    .filter(|r| {
                        let o = embree.occluded(r);
                        g8w.occluded(r) == o && w8.occluded(r) == o
                    })
                    .count() as f64
                    / rays.len() as f64;
                println!(
                    "{label:>5} {tris:>8} {:>6.1} ms {:>6.1} ms {:>6.1} ms {:>9.2} {:>9.2} {:>9.2} \
                     {:>6.2} {:>6.2} {:>6.2}%  {kind} {}",
                    bg * 1e3,
                    b8 * 1e3,
                    eb * 1e3,
                    rg / 1e6,
                    r8 / 1e6,
                    e / 1e6,
                    rg / e,
                    r8 / e,
                    agree * 100.0,
                    if any { "any" } else { "closest" }
                );
            }
        }
    }
}

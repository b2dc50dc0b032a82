//! Tessera's ray casts against Embree 3's single-ray queries (`rtcIntersect1`, `rtcOccluded1`)
//! on the same meshes and rays, in the same run: rays per CPU-second, best of 5 alternating
//! rounds, one thread; also the build time of each (Embree with `threads=1`) and how often the
//! two agree on hit or miss.
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
    rays_per_second, wanted_sizes,
};
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

fn main() {
    let camera = camera_rays(256);
    let random = random_rays(1 << 16, 7);
    println!(
        "{:>5} {:>8} {:>14} {:>14} {:>13} {:>13} {:>6} {:>7}",
        "mesh",
        "tris",
        "tessera build",
        "embree build",
        "tessera Mr/s",
        "embree Mr/s",
        "ratio",
        "agree"
    );
    for (label, target) in wanted_sizes() {
        let (positions, indices) = bumpy_sphere(frequency_for(target));
        let pos: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
        let start = Instant::now();
        let embree = Embree::new(&pos, &indices);
        let eb = start.elapsed().as_secs_f64();
        let parts = mesh_parts(positions, indices);
        let start = Instant::now();
        let scene = Scene::with_build_params(parts, build_params()).expect("valid scene");
        let tb = start.elapsed().as_secs_f64();
        let tris = scene.prims.len();
        for (kind, rays) in [("camera", &camera), ("random", &random)] {
            for any in [false, true] {
                let (mut t, mut e) = (0.0f64, 0.0f64);
                for _ in 0..5 {
                    if any {
                        t = t.max(rays_per_second(rays, 1, |r| scene.occluded(r)));
                        e = e.max(rays_per_second(rays, 1, |r| embree.occluded(r)));
                    } else {
                        t = t.max(rays_per_second(rays, 1, |r| {
                            scene.intersect_hit(r).is_some()
                        }));
                        e = e.max(rays_per_second(rays, 1, |r| embree.intersect(r).is_some()));
                    }
                }
                let agree = rays
                    .iter()
                    .filter(|r| scene.occluded(r) == embree.occluded(r))
                    .count() as f64
                    / rays.len() as f64;
                println!(
                    "{label:>5} {tris:>8} {:>11.1} ms {:>11.1} ms {:>13.2} {:>13.2} {:>6.2} {:>6.2}%  \
                     {kind} {}",
                    tb * 1e3,
                    eb * 1e3,
                    t / 1e6,
                    e / 1e6,
                    t / e,
                    agree * 100.0,
                    if any { "any" } else { "closest" }
                );
            }
        }
    }
}

//! Embree 3 through a hand-written FFI, for the comparison benches (`embree`, `embree_small`):
//! only the few calls they use, with the structs of `embree3/rtcore_ray.h` and
//! `rtcore_common.h` (3.13, built with `RTC_MAX_INSTANCE_LEVEL_COUNT 1` and `RTC_MIN_WIDTH 0` as
//! Debian's is). Tessera itself never links Embree.
#![allow(unsafe_code)]
use glam::Vec3;
use std::ffi::{c_char, c_void};
use tessera_core::math::Ray;

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
/// `RTC_SCENE_FLAG_ROBUST`: "avoid optimizations that reduce arithmetic accuracy". Embree 3 then
/// stores each leaf's triangle corners (`Triangle4v`, as Tessera's blocks do) and runs the
/// watertight Pluecker test with conservative node tests: the guarantees Tessera's casts give.
const SCENE_FLAG_ROBUST: u32 = 1 << 2;
/// `RTC_BUILD_QUALITY_HIGH`: a builder with spatial splits.
const BUILD_QUALITY_HIGH: u32 = 2;
/// `RTC_INTERSECT_CONTEXT_FLAG_COHERENT`: the rays of a packet are coherent.
const CONTEXT_FLAG_COHERENT: u32 = 1;
/// The ray's start. Tessera's rays cover `t` in `(0, t_max)`; Embree's test accepts
/// `t >= tnear`, and in robust mode it reports a ray that starts exactly on a surface (an origin
/// with a zero coordinate on a wall at zero, whose offset is zero) as hitting it at `t = 0`.
/// The least positive float excludes `t = 0` as Tessera does, and nothing else.
const TNEAR: f32 = f32::MIN_POSITIVE;

#[link(name = "embree3")]
extern "C" {
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba12rtcNewDeviceEPKc"
    )]
    fn rtcNewDevice(config: *const c_char) -> *mut c_void;
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba16rtcReleaseDeviceEPNS_11RTCDeviceTyE"
    )]
    fn rtcReleaseDevice(device: *mut c_void);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba17rtcGetDeviceErrorEPNS_11RTCDeviceTyE"
    )]
    fn rtcGetDeviceError(device: *mut c_void) -> u32;
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba11rtcNewSceneEPNS_11RTCDeviceTyE"
    )]
    fn rtcNewScene(device: *mut c_void) -> *mut c_void;
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba15rtcReleaseSceneEPNS_10RTCSceneTyE"
    )]
    fn rtcReleaseScene(scene: *mut c_void);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba14rtcNewGeometryEPNS_11RTCDeviceTyENS_15RTCGeometryTypeE"
    )]
    fn rtcNewGeometry(device: *mut c_void, kind: u32) -> *mut c_void;
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba26rtcSetSharedGeometryBufferEPNS_13RTCGeometryTyENS_13RTCBufferTypeEjNS_9RTCFormatEPKvmmm"
    )]
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
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba17rtcCommitGeometryEPNS_13RTCGeometryTyE"
    )]
    fn rtcCommitGeometry(geometry: *mut c_void);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba17rtcAttachGeometryEPNS_10RTCSceneTyEPNS_13RTCGeometryTyE"
    )]
    fn rtcAttachGeometry(scene: *mut c_void, geometry: *mut c_void) -> u32;
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba18rtcReleaseGeometryEPNS_13RTCGeometryTyE"
    )]
    fn rtcReleaseGeometry(geometry: *mut c_void);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba14rtcCommitSceneEPNS_10RTCSceneTyE"
    )]
    fn rtcCommitScene(scene: *mut c_void);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba16rtcSetSceneFlagsEPNS_10RTCSceneTyENS_13RTCSceneFlagsE"
    )]
    fn rtcSetSceneFlags(scene: *mut c_void, flags: u32);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba23rtcSetSceneBuildQualityEPNS_10RTCSceneTyENS_15RTCBuildQualityE"
    )]
    fn rtcSetSceneBuildQuality(scene: *mut c_void, quality: u32);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba13rtcIntersect1EPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_9RTCRayHitE"
    )]
    fn rtcIntersect1(scene: *mut c_void, ctx: *mut RtcIntersectContext, rayhit: *mut RtcRayHit);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba12rtcOccluded1EPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_6RTCRayE"
    )]
    fn rtcOccluded1(scene: *mut c_void, ctx: *mut RtcIntersectContext, ray: *mut RtcRay);
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba13rtcIntersect8EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_10RTCRayHit8E"
    )]
    fn rtcIntersect8(
        valid: *const i32,
        scene: *mut c_void,
        ctx: *mut RtcIntersectContext,
        rayhit: *mut RtcRayHitN<8>,
    );
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba12rtcOccluded8EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_7RTCRay8E"
    )]
    fn rtcOccluded8(
        valid: *const i32,
        scene: *mut c_void,
        ctx: *mut RtcIntersectContext,
        ray: *mut RtcRayN<8>,
    );
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba14rtcIntersect16EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_11RTCRayHit16E"
    )]
    fn rtcIntersect16(
        valid: *const i32,
        scene: *mut c_void,
        ctx: *mut RtcIntersectContext,
        rayhit: *mut RtcRayHitN<16>,
    );
    #[cfg_attr(
        feature = "embree-mitsuba",
        link_name = "_ZN7mitsuba13rtcOccluded16EPKiPNS_10RTCSceneTyEPNS_19RTCIntersectContextEPNS_8RTCRay16E"
    )]
    fn rtcOccluded16(
        valid: *const i32,
        scene: *mut c_void,
        ctx: *mut RtcIntersectContext,
        ray: *mut RtcRayN<16>,
    );
}

/// `RTCRay8` / `RTCRay16`: a packet of rays, one array per field (64-byte aligned, as the
/// header's `RTC_ALIGN(64)` for the 16-wide one; the 8-wide one needs 32).
#[repr(C, align(64))]
#[derive(Clone, Copy)]
pub struct RtcRayN<const N: usize> {
    org: [[f32; N]; 3],
    tnear: [f32; N],
    dir: [[f32; N]; 3],
    time: [f32; N],
    tfar: [f32; N],
    mask: [u32; N],
    id: [u32; N],
    flags: [u32; N],
}

/// `RTCHit8` / `RTCHit16`.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
struct RtcHitN<const N: usize> {
    ng: [[f32; N]; 3],
    u: [f32; N],
    v: [f32; N],
    prim_id: [u32; N],
    geom_id: [u32; N],
    inst_id: [[u32; N]; 1],
}

/// `RTCRayHit8` / `RTCRayHit16`.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
pub struct RtcRayHitN<const N: usize> {
    ray: RtcRayN<N>,
    hit: RtcHitN<N>,
}

impl<const N: usize> RtcRayHitN<N> {
    /// `ray` with no hit yet (every id invalid), for a closest-hit call.
    fn unhit(ray: RtcRayN<N>) -> Self {
        RtcRayHitN {
            ray,
            hit: RtcHitN {
                ng: [[0.0; N]; 3],
                u: [0.0; N],
                v: [0.0; N],
                prim_id: [INVALID_ID; N],
                geom_id: [INVALID_ID; N],
                inst_id: [[INVALID_ID; N]],
            },
        }
    }
}

/// The valid mask of a packet: -1 for every lane in use.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
struct Valid<const N: usize>([i32; N]);

impl<const N: usize> RtcRayN<N> {
    /// A packet of `rays` (at most `N`; the lanes beyond are masked off by the caller's valid
    /// mask).
    fn of(rays: &[Ray]) -> Self {
        let mut p = RtcRayN {
            org: [[0.0; N]; 3],
            tnear: [TNEAR; N],
            dir: [[0.0; N]; 3],
            time: [0.0; N],
            tfar: [0.0; N],
            mask: [u32::MAX; N],
            id: [0; N],
            flags: [0; N],
        };
        for (i, r) in rays.iter().enumerate() {
            for a in 0..3 {
                p.org[a][i] = r.o[a];
                p.dir[a][i] = r.d[a];
            }
            p.tfar[i] = r.t_max;
        }
        p
    }
}

fn valid<const N: usize>(n: usize) -> Valid<N> {
    let mut v = Valid([0; N]);
    v.0[..n].fill(-1);
    v
}

/// An Embree device and scene over one triangle mesh whose buffers it shares (kept alive here).
pub struct Embree {
    device: *mut c_void,
    scene: *mut c_void,
    _vertices: Vec<f32>,
    _indices: Vec<u32>,
}

/// Which of Embree's two modes a scene is built in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The default flags: its fastest triangle test (not watertight).
    Fast,
    /// `RTC_SCENE_FLAG_ROBUST`: a watertight triangle test, as Tessera's.
    Robust,
    /// As Mitsuba 3 builds its scenes (`scripts/mitsuba_rays/run.sh` prints the settings): the
    /// default flags and `RTC_BUILD_QUALITY_HIGH` (spatial splits). Mitsuba also marks its camera
    /// rays' packets coherent: [`Embree::intersect16_coherent`].
    Mitsuba,
}

/// Embree's device configuration: one thread, plus `EMBREE_CONFIG` if set (for example
/// `EMBREE_CONFIG=isa=avx2` to time Embree's AVX2 kernels on a host where it would pick AVX-512).
fn device_config() -> std::ffi::CString {
    let extra = std::env::var("EMBREE_CONFIG").unwrap_or_default();
    let config = if extra.is_empty() {
        "threads=1".to_string()
    } else {
        format!("threads=1,{extra}")
    };
    std::ffi::CString::new(config).expect("EMBREE_CONFIG has no NUL byte")
}

impl Embree {
    /// A scene of one triangle mesh in the default (fast) mode.
    pub fn new(positions: &[[f32; 3]], indices: &[[u32; 3]]) -> Embree {
        Self::with_mode(positions, indices, Mode::Fast)
    }

    /// A scene of one triangle mesh in `mode`.
    pub fn with_mode(positions: &[[f32; 3]], indices: &[[u32; 3]], mode: Mode) -> Embree {
        // Embree reads vertex buffers 16 bytes at a time: one float of padding at the end.
        let mut vertices: Vec<f32> = positions.iter().flatten().copied().collect();
        vertices.push(0.0);
        let idx: Vec<u32> = indices.iter().flatten().copied().collect();
        let config = device_config();
        // SAFETY: the config is a NUL-terminated string; every handle passed on is the non-null
        // one Embree returned (checked); the shared buffers point into `vertices` and `idx`, whose
        // heap storage lives (unmoved) in the returned struct as long as the scene.
        unsafe {
            let device = rtcNewDevice(config.as_ptr());
            assert!(!device.is_null(), "rtcNewDevice failed");
            let scene = rtcNewScene(device);
            let geom = rtcNewGeometry(device, GEOMETRY_TYPE_TRIANGLE);
            assert!(
                !scene.is_null() && !geom.is_null(),
                "Embree scene or geometry"
            );
            if mode == Mode::Robust {
                rtcSetSceneFlags(scene, SCENE_FLAG_ROBUST);
            }
            if mode == Mode::Mitsuba {
                rtcSetSceneBuildQuality(scene, BUILD_QUALITY_HIGH);
            }
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
            tnear: TNEAR,
            dir: r.d.to_array(),
            time: 0.0,
            tfar: r.t_max,
            mask: u32::MAX,
            id: 0,
            flags: 0,
        }
    }

    fn context(flags: u32) -> RtcIntersectContext {
        // As `rtcInitIntersectContext` (an inline function in the header).
        RtcIntersectContext {
            flags,
            filter: None,
            inst_id: [INVALID_ID],
        }
    }

    /// Closest hit: `(t, primitive)`.
    pub fn intersect(&self, r: &Ray) -> Option<(f32, u32)> {
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
        let mut ctx = Self::context(0);
        // SAFETY: `self.scene` is a committed scene; `ctx` and `rh` are valid, aligned locals.
        unsafe { rtcIntersect1(self.scene, &mut ctx, &mut rh) };
        (rh.hit.geom_id != INVALID_ID).then_some((rh.ray.tfar, rh.hit.prim_id))
    }

    pub fn occluded(&self, r: &Ray) -> bool {
        let mut ray = Self::ray(r);
        let mut ctx = Self::context(0);
        // SAFETY: as in `intersect`.
        unsafe { rtcOccluded1(self.scene, &mut ctx, &mut ray) };
        ray.tfar == f32::NEG_INFINITY
    }
}

/// `rtcIntersect8` / `rtcIntersect16`.
type IntersectN<const N: usize> =
    unsafe extern "C" fn(*const i32, *mut c_void, *mut RtcIntersectContext, *mut RtcRayHitN<N>);
/// `rtcOccluded8` / `rtcOccluded16`.
type OccludedN<const N: usize> =
    unsafe extern "C" fn(*const i32, *mut c_void, *mut RtcIntersectContext, *mut RtcRayN<N>);

impl Embree {
    /// Closest hits of up to `N` rays in one packet call `f`: how many hit something.
    fn intersect_packet<const N: usize>(
        &self,
        rays: &[Ray],
        f: IntersectN<N>,
        flags: u32,
    ) -> usize {
        let mut rh = RtcRayHitN::<N>::unhit(RtcRayN::of(rays));
        let (v, mut ctx) = (valid::<N>(rays.len()), Self::context(flags));
        // SAFETY: `f` is Embree's packet call of width `N`; `self.scene` is a committed scene;
        // the mask, context and packet are valid, suitably aligned locals with the header's
        // layouts.
        unsafe { f(v.0.as_ptr(), self.scene, &mut ctx, &mut rh) };
        rh.hit.geom_id[..rays.len()]
            .iter()
            .filter(|&&g| g != INVALID_ID)
            .count()
    }

    /// Any-hit tests of up to `N` rays in one packet call `f`: how many are blocked.
    fn occluded_packet<const N: usize>(&self, rays: &[Ray], f: OccludedN<N>) -> usize {
        let mut r = RtcRayN::<N>::of(rays);
        let (v, mut ctx) = (valid::<N>(rays.len()), Self::context(0));
        // SAFETY: as in `intersect_packet`.
        unsafe { f(v.0.as_ptr(), self.scene, &mut ctx, &mut r) };
        r.tfar[..rays.len()]
            .iter()
            .filter(|&&t| t == f32::NEG_INFINITY)
            .count()
    }

    /// Closest hits of up to 8 rays in one `rtcIntersect8` call.
    pub fn intersect8(&self, rays: &[Ray]) -> usize {
        self.intersect_packet::<8>(rays, rtcIntersect8, 0)
    }

    /// Closest hits of up to 16 rays in one `rtcIntersect16` call.
    pub fn intersect16(&self, rays: &[Ray]) -> usize {
        self.intersect_packet::<16>(rays, rtcIntersect16, 0)
    }

    /// The same, with the packet marked coherent (`RTC_INTERSECT_CONTEXT_FLAG_COHERENT`), as
    /// Mitsuba 3 marks its camera rays.
    pub fn intersect16_coherent(&self, rays: &[Ray]) -> usize {
        self.intersect_packet::<16>(rays, rtcIntersect16, CONTEXT_FLAG_COHERENT)
    }

    /// Any-hit tests of up to 8 rays in one `rtcOccluded8` call.
    pub fn occluded8(&self, rays: &[Ray]) -> usize {
        self.occluded_packet::<8>(rays, rtcOccluded8)
    }

    /// Any-hit tests of up to 16 rays in one `rtcOccluded16` call.
    pub fn occluded16(&self, rays: &[Ray]) -> usize {
        self.occluded_packet::<16>(rays, rtcOccluded16)
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

/// A 16-wide packet exactly as a renderer handed it to Embree: the valid mask and the ray
/// fields, lanes not in use included (they keep whatever the renderer left there).
#[derive(Clone, Copy)]
pub struct RawPacket16 {
    valid: Valid<16>,
    ray: RtcRayN<16>,
    /// The context flags of the recorded call.
    flags: u32,
}

impl RawPacket16 {
    /// The rays of the active lanes, in lane order (Tessera's rays start at `t > 0`, so the
    /// recorded `tnear` must be 0).
    pub fn rays(&self) -> Vec<Ray> {
        let r = &self.ray;
        (0..16)
            .filter(|&i| self.valid.0[i] != 0)
            .map(|i| {
                assert!(r.tnear[i] == 0.0, "a recorded ray with tnear > 0");
                Ray {
                    o: Vec3::new(r.org[0][i], r.org[1][i], r.org[2][i]),
                    d: Vec3::new(r.dir[0][i], r.dir[1][i], r.dir[2][i]),
                    t_max: r.tfar[i],
                }
            })
            .collect()
    }

    /// From the 16 mask words, the 12 x 16 ray words (org x/y/z, tnear, dir x/y/z, time, tfar,
    /// mask, id, flags) and the call's context flags, as `scripts/mitsuba_rays/shim.c` records
    /// them.
    pub fn from_words(valid: &[i32; 16], ray: &[u32; 192], flags: u32) -> Self {
        let lane = |f: usize| -> [u32; 16] { ray[16 * f..16 * f + 16].try_into().unwrap() };
        let float = |f: usize| lane(f).map(f32::from_bits);
        RawPacket16 {
            valid: Valid(*valid),
            ray: RtcRayN {
                org: [float(0), float(1), float(2)],
                tnear: float(3),
                dir: [float(4), float(5), float(6)],
                time: float(7),
                tfar: float(8),
                mask: lane(9),
                id: lane(10),
                flags: lane(11),
            },
            flags,
        }
    }
}

impl Embree {
    /// Closest hits of a recorded packet, cast as recorded (with its recorded context flags when
    /// `recorded_flags`, else none): how many active lanes hit.
    pub fn intersect16_raw(&self, p: &RawPacket16, recorded_flags: bool) -> usize {
        let mut rh = RtcRayHitN::unhit(p.ray);
        let mut ctx = Self::context(if recorded_flags { p.flags } else { 0 });
        // SAFETY: as in `intersect_packet`; the mask is the recorded one.
        unsafe { rtcIntersect16(p.valid.0.as_ptr(), self.scene, &mut ctx, &mut rh) };
        (0..16)
            .filter(|&i| p.valid.0[i] != 0 && rh.hit.geom_id[i] != INVALID_ID)
            .count()
    }

    /// Any-hit tests of a recorded packet, cast as recorded (flags as in `intersect16_raw`): how
    /// many active lanes are blocked.
    pub fn occluded16_raw(&self, p: &RawPacket16, recorded_flags: bool) -> usize {
        let mut r = p.ray;
        let mut ctx = Self::context(if recorded_flags { p.flags } else { 0 });
        // SAFETY: as in `intersect_packet`; the mask is the recorded one.
        unsafe { rtcOccluded16(p.valid.0.as_ptr(), self.scene, &mut ctx, &mut r) };
        (0..16)
            .filter(|&i| p.valid.0[i] != 0 && r.tfar[i] == f32::NEG_INFINITY)
            .count()
    }
}

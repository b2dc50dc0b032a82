//! Inputs for Tessera's micro-benchmarks (`cargo bench -p tessera-benches`): procedural meshes
//! of a chosen size, scenes holding them, and batches of coherent and incoherent rays. Nothing
//! is read from disk, so the benchmarks need no big files in the repository.
use glam::{Vec2, Vec3};
use std::time::Instant;
use tessera_core::accel::tri_block::Ray4;
use tessera_core::accel::{
    AnyLeaves, BuildParams, Bvh, Bvh8, ClosestLeaves, Collapse, LeafRanges, TriBlocks,
};
use tessera_core::bsdf::{Bsdf, Diffuse};
use tessera_core::camera::{Camera, Filter, FovAxis};
use tessera_core::geometry::{intersect_triangle, Hit, Mesh, Shape, ShapeKind};
use tessera_core::math::{Aabb, Norm, Ray, Transform};
use tessera_core::scene::{Scene, SceneParts};
use tessera_core::texture::Texture;

/// The `tessera` binary's allocator (jemalloc with transparent huge pages), so the benches time
/// casts in memory laid out as a render's is.
#[cfg(not(target_env = "msvc"))]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

/// A small deterministic generator (SplitMix64).
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn f(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform on the unit sphere.
    pub fn dir(&mut self) -> Vec3 {
        let z = 1.0 - 2.0 * self.f();
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = std::f32::consts::TAU * self.f();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// Triangles of a geodesic sphere of frequency `n`: each icosahedron face cut into n^2.
pub fn geodesic_triangles(n: u32) -> usize {
    20 * (n as usize) * (n as usize)
}

/// The smallest geodesic frequency with at least `triangles` triangles.
pub fn frequency_for(triangles: usize) -> u32 {
    let mut n = 1;
    while geodesic_triangles(n) < triangles {
        n += 1;
    }
    n
}

/// A bumpy geodesic sphere of radius about 1 with `20 n^2` triangles: the icosahedron's faces
/// are subdivided `n` times per edge, projected to the sphere and displaced radially by a smooth
/// function of position, so the mesh is not a perfect sphere (the BVH sees uneven boxes).
/// Vertices on face edges are duplicated (each face is its own grid), which costs memory but
/// does not change what rays hit.
pub fn bumpy_sphere(n: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let v = [
        Vec3::new(-1.0, t, 0.0),
        Vec3::new(1.0, t, 0.0),
        Vec3::new(-1.0, -t, 0.0),
        Vec3::new(1.0, -t, 0.0),
        Vec3::new(0.0, -1.0, t),
        Vec3::new(0.0, 1.0, t),
        Vec3::new(0.0, -1.0, -t),
        Vec3::new(0.0, 1.0, -t),
        Vec3::new(t, 0.0, -1.0),
        Vec3::new(t, 0.0, 1.0),
        Vec3::new(-t, 0.0, -1.0),
        Vec3::new(-t, 0.0, 1.0),
    ];
    const FACES: [[usize; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let displace = |p: Vec3| {
        let d = p.unit();
        let r = 1.0
            + 0.08 * (9.0 * d.x).sin() * (7.0 * d.y).sin() * (5.0 * d.z).sin()
            + 0.03 * (23.0 * d.x + 17.0 * d.z).sin();
        d * r
    };
    let n = n.max(1);
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for f in FACES {
        let (a, b, c) = (v[f[0]], v[f[1]], v[f[2]]);
        let base = positions.len() as u32;
        // Grid point (i, j), i + j <= n, at a + (b - a) i/n + (c - a) j/n.
        let id = |i: u32, j: u32| base + i * (n + 1) - i * i.saturating_sub(1) / 2 + j;
        let mut count = 0;
        for i in 0..=n {
            for j in 0..=(n - i) {
                let p = a + (b - a) * (i as f32 / n as f32) + (c - a) * (j as f32 / n as f32);
                positions.push(displace(p));
                debug_assert_eq!(id(i, j), base + count);
                count += 1;
            }
        }
        for i in 0..n {
            for j in 0..(n - i) {
                indices.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                if i + j + 1 < n {
                    indices.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
        }
    }
    (positions, indices)
}

/// Scene parts holding one mesh (diffuse, no lights).
pub fn mesh_parts(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> SceneParts {
    SceneParts {
        shapes: vec![Shape {
            kind: ShapeKind::Mesh(Mesh::new(positions, vec![], vec![], indices)),
            bsdf: 0,
            emitter: None,
            flip_normals: false,
        }],
        disks: vec![],
        bsdfs: vec![Bsdf::Diffuse(Diffuse {
            reflectance: Texture::constant(0.5),
        })],
        emitters: vec![],
        camera: Camera::perspective(Transform::IDENTITY, 4, 4, 40.0, FovAxis::X, 0.01, 1e4),
        filter: Filter::Box,
        light_selection: Default::default(),
        groups: Vec::new(),
        instances: Vec::new(),
    }
}

/// A scene holding a bumpy sphere with at least `triangles` triangles.
pub fn sphere_scene(triangles: usize) -> Scene {
    let (p, i) = bumpy_sphere(frequency_for(triangles));
    Scene::new(mesh_parts(p, i)).expect("a valid mesh scene")
}

/// Coherent primary rays: a pinhole 3.5 units away looking at the sphere, `side x side` rays in
/// scanline order over a field of view that just frames it (most rays hit).
pub fn camera_rays(side: u32) -> Vec<Ray> {
    let o = Vec3::new(0.0, 0.0, 3.5);
    let half = 0.28;
    let mut out = Vec::with_capacity((side * side) as usize);
    for y in 0..side {
        for x in 0..side {
            let p = Vec2::new(
                (x as f32 + 0.5) / side as f32 * 2.0 - 1.0,
                1.0 - (y as f32 + 0.5) / side as f32 * 2.0,
            ) * half;
            out.push(Ray::new(o, Vec3::new(p.x, p.y, -1.0).unit()));
        }
    }
    out
}

/// Incoherent rays: origins uniform in the cube [-1.2, 1.2]^3 (mostly inside the sphere, like
/// bounces), directions uniform on the sphere; every ray has its own direction and origin.
pub fn random_rays(count: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    (0..count)
        .map(|_| {
            let o = Vec3::new(rng.f(), rng.f(), rng.f()) * 2.4 - Vec3::splat(1.2);
            Ray::new(o, rng.dir())
        })
        .collect()
}

/// Bytes per triangle of the ray-casting data: (BVH nodes, triangle blocks,
/// primitive references: shape and face).
pub fn bytes_per_triangle(scene: &Scene) -> (f64, f64, f64) {
    let n = scene.prims.len().max(1) as f64;
    let m = scene.accel_memory();
    (
        m.nodes as f64 / n,
        m.triangles as f64 / n,
        m.prims as f64 / n,
    )
}

/// A triangle as scenes stored it before the wide BVHs: corners inline with shape and face ids
/// (padded to 48 bytes like the old primitive enum).
#[derive(Clone, Copy)]
pub struct OldTriangle {
    /// Corners.
    pub v: [Vec3; 3],
    /// Shape, face, and the enum's tag and padding.
    pub ids: [u32; 3],
}

/// The binary SAH BVH over a scene's triangles, traversed as scenes did before the wide BVHs
/// (one box per step, near child first by the split axis, the triangle test's per-ray setup
/// redone per triangle): the baseline of the comparison. Triangle meshes only.
pub struct BinaryScene {
    /// The binary hierarchy.
    pub bvh: Bvh,
    /// The triangles in this hierarchy's order.
    pub tris: Vec<OldTriangle>,
}

impl BinaryScene {
    /// Builds the binary hierarchy over `scene`'s triangles.
    pub fn new(scene: &Scene) -> BinaryScene {
        let corners: Vec<[Vec3; 3]> = (0..scene.prims.len())
            .map(|i| scene.triangle(i).expect("a triangle mesh"))
            .collect();
        let bounds: Vec<_> = corners
            .iter()
            .map(|v| Aabb::point(v[0]).grow(v[1]).grow(v[2]))
            .collect();
        let (bvh, order) = Bvh::build(&bounds);
        BinaryScene {
            bvh,
            tris: order
                .iter()
                .map(|&i| OldTriangle {
                    v: corners[i as usize],
                    ids: [0, i, 0],
                })
                .collect(),
        }
    }

    #[inline(always)]
    fn hit(&self, i: usize, ray: &Ray, t_max: f32) -> Option<f32> {
        let v = &self.tris[i].v;
        intersect_triangle(ray, t_max, v[0], v[1], v[2]).map(|h| h.0)
    }

    /// Closest hit: `(t, triangle index in this order)`.
    pub fn intersect_hit(&self, ray: &Ray) -> Option<(f32, u32)> {
        let mut best = None;
        self.bvh.traverse(ray, |first, count, mut t_max| {
            for i in first..first + count {
                if let Some(t) = self.hit(i, ray, t_max) {
                    t_max = t;
                    best = Some((t, i as u32));
                }
            }
            Some(t_max)
        });
        best
    }

    /// Any hit.
    pub fn occluded(&self, ray: &Ray) -> bool {
        let mut hit = false;
        self.bvh.traverse(ray, |first, count, t_max| {
            for i in first..first + count {
                if self.hit(i, ray, t_max).is_some() {
                    hit = true;
                    return None;
                }
            }
            Some(t_max)
        });
        hit
    }
}

/// The test of primitives that are not triangles, for meshes (there are none).
pub type NoOther = fn(usize, &[Vec3; 3], f32) -> Option<(f32, Vec2)>;

fn no_other(_: usize, _: &[Vec3; 3], _: f32) -> Option<(f32, Vec2)> {
    None
}

/// An 8-wide BVH (of either collapse: [`Bvh8`], [`Bvh8Greedy`]) as [`WideScene`] traverses it.
pub trait WideBvh: LeafRanges + Sized {
    /// Builds over primitive boxes: the hierarchy and the primitive order.
    fn build_with(bounds: &[Aabb], params: BuildParams) -> (Self, Vec<u32>);
    /// Closest-hit cast over triangle blocks (as the scene's).
    fn closest(&self, ray: &Ray, leaves: ClosestLeaves<'_, NoOther>);
    /// Any-hit cast over triangle blocks; returns whether a hit was found.
    fn any(&self, ray: &Ray, leaves: AnyLeaves<'_, NoOther>) -> bool;
    /// Bytes of the nodes.
    fn node_bytes(&self) -> usize;
}

impl WideBvh for Bvh8 {
    fn build_with(bounds: &[Aabb], params: BuildParams) -> (Self, Vec<u32>) {
        Bvh8::build_collapsed(bounds, params, collapse())
    }
    #[inline(always)]
    fn closest(&self, ray: &Ray, leaves: ClosestLeaves<'_, NoOther>) {
        self.cast::<false>(ray, leaves)
    }
    #[inline(always)]
    fn any(&self, ray: &Ray, mut leaves: AnyLeaves<'_, NoOther>) -> bool {
        self.cast::<true>(ray, &mut leaves);
        leaves.hit
    }
    fn node_bytes(&self) -> usize {
        self.memory_bytes()
    }
}

/// The 8-wide BVH collapsed greedily (the first collapse: open the largest interior child), to
/// compare with the default collapse in the same run.
pub struct Bvh8Greedy(pub Bvh8);

impl LeafRanges for Bvh8Greedy {
    fn map_leaves(&mut self, f: impl FnMut(usize, usize) -> u32) {
        self.0.map_leaves(f);
    }
}

impl WideBvh for Bvh8Greedy {
    fn build_with(bounds: &[Aabb], params: BuildParams) -> (Self, Vec<u32>) {
        let (b, order) = Bvh8::build_collapsed(bounds, params, Collapse::Greedy);
        (Bvh8Greedy(b), order)
    }
    #[inline(always)]
    fn closest(&self, ray: &Ray, leaves: ClosestLeaves<'_, NoOther>) {
        self.0.cast::<false>(ray, leaves)
    }
    #[inline(always)]
    fn any(&self, ray: &Ray, mut leaves: AnyLeaves<'_, NoOther>) -> bool {
        self.0.cast::<true>(ray, &mut leaves);
        leaves.hit
    }
    fn node_bytes(&self) -> usize {
        self.0.memory_bytes()
    }
}

/// The 8-wide collapse: [`Collapse::DEFAULT`], or `BVH8_COLLAPSE=greedy` or
/// `BVH8_COLLAPSE=node_cost,block_cost,max_leaf` (the surface-area collapse with these).
pub fn collapse() -> Collapse {
    let Ok(v) = std::env::var("BVH8_COLLAPSE").map(|v| v.trim().to_string()) else {
        return Collapse::DEFAULT;
    };
    if v.is_empty() {
        return Collapse::DEFAULT;
    }
    if v == "greedy" {
        return Collapse::Greedy;
    }
    let f: Vec<&str> = v.split(',').collect();
    assert!(
        f.len() == 3,
        "BVH8_COLLAPSE=greedy or node_cost,block_cost,max_leaf"
    );
    Collapse::Sah {
        node_cost: f[0].parse().expect("node_cost"),
        block_cost: f[1].parse().expect("block_cost"),
        max_leaf: f[2].parse().expect("max_leaf"),
    }
}

/// A scene's triangles under an 8-wide BVH of either collapse, with the scene's leaf code
/// (blocks of four triangles, [`TriBlocks`]): compares the collapses whatever [`Scene`] itself
/// uses. Triangle meshes only.
pub struct WideScene<B> {
    /// The hierarchy; leaves refer to blocks.
    pub bvh: B,
    /// The triangle blocks.
    pub blocks: TriBlocks,
    /// Scene primitive index of each position of this hierarchy's order.
    pub order: Vec<u32>,
}

impl<B: WideBvh> WideScene<B> {
    /// Builds over `scene`'s triangles with `params`.
    pub fn new(scene: &Scene, params: BuildParams) -> WideScene<B> {
        let corners: Vec<[Vec3; 3]> = (0..scene.prims.len())
            .map(|i| scene.triangle(i).expect("a triangle mesh"))
            .collect();
        let bounds: Vec<_> = corners
            .iter()
            .map(|v| Aabb::point(v[0]).grow(v[1]).grow(v[2]))
            .collect();
        let (mut bvh, order) = B::build_with(&bounds, params);
        let sorted: Vec<[Vec3; 3]> = order.iter().map(|&i| corners[i as usize]).collect();
        let blocks = TriBlocks::build(&mut bvh, &sorted);
        WideScene { bvh, blocks, order }
    }

    /// Closest hit (`prim` is the scene's primitive index).
    #[inline]
    pub fn intersect_hit(&self, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let r4 = Ray4::from_ray(ray);
        self.bvh.closest(
            ray,
            ClosestLeaves {
                blocks: &self.blocks,
                ray: &r4,
                best: &mut best,
                other: no_other,
            },
        );
        best.map(|h| Hit {
            prim: self.order[h.prim as usize],
            ..h
        })
    }

    /// Any hit.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        let r4 = Ray4::from_ray(ray);
        self.bvh.any(
            ray,
            AnyLeaves {
                blocks: &self.blocks,
                ray: &r4,
                hit: false,
                other: no_other,
            },
        )
    }

    /// Bytes per triangle: nodes, blocks.
    pub fn bytes_per_triangle(&self) -> (f64, f64) {
        let n = self.order.len().max(1) as f64;
        (
            self.bvh.node_bytes() as f64 / n,
            self.blocks.memory_bytes() as f64 / n,
        )
    }
}

/// CPU time this thread has run, in seconds (Linux `/proc/thread-self/schedstat`), or `None`
/// where unavailable. On a loaded machine it measures the work, not the wait for a core.
pub fn thread_cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns as f64 * 1e-9)
}

/// A clock: thread CPU time where available, else wall time since `start`.
fn clock(start: Instant) -> f64 {
    thread_cpu_seconds().unwrap_or_else(|| start.elapsed().as_secs_f64())
}

/// Rays per second of `cast` over `rays` (per second of this thread's CPU time where the OS
/// reports it, else of wall time), best of `rounds` passes of at least 0.2 s each.
pub fn rays_per_second(rays: &[Ray], rounds: usize, mut cast: impl FnMut(&Ray) -> bool) -> f64 {
    let mut best = 0.0f64;
    let epoch = Instant::now();
    for _ in 0..rounds {
        let start = clock(epoch);
        let mut passes = 0usize;
        let mut found = 0usize;
        while passes == 0 || clock(epoch) - start < 0.2 {
            for r in rays {
                found += usize::from(cast(std::hint::black_box(r)));
            }
            passes += 1;
        }
        std::hint::black_box(found);
        best = best.max((passes * rays.len()) as f64 / (clock(epoch) - start));
    }
    best
}

/// The mesh sizes every ray-casting bench measures: (label, about how many triangles).
pub const MESH_SIZES: [(&str, usize); 4] = [
    ("1k", 1_000),
    ("10k", 10_000),
    ("100k", 100_000),
    ("1M", 1_000_000),
];

/// The mesh sizes named on the command line (`cargo bench ... -- 1k 100k`), or all of them.
pub fn wanted_sizes() -> Vec<(&'static str, usize)> {
    let wanted: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    MESH_SIZES
        .into_iter()
        .filter(|(label, _)| wanted.is_empty() || wanted.iter().any(|w| w == label))
        .collect()
}

/// The binary build's parameters (that of every hierarchy the benches build but the binary
/// baseline's): `Bvh8::PARAMS`, or those of the environment variable
/// `BVH_PARAMS=max_leaf,traversal_cost,block` (for measuring other trade-offs).
pub fn build_params() -> tessera_core::accel::BuildParams {
    let Ok(v) = std::env::var("BVH_PARAMS") else {
        return tessera_core::accel::Bvh8::PARAMS;
    };
    let f: Vec<&str> = v.split(',').collect();
    assert!(f.len() == 3, "BVH_PARAMS=max_leaf,traversal_cost,block");
    let p = tessera_core::accel::BuildParams {
        max_leaf: f[0].parse().expect("max_leaf"),
        traversal_cost: f[1].parse().expect("traversal_cost"),
        block: f[2].parse().expect("block"),
    };
    eprintln!("BVH_PARAMS: {p:?}");
    p
}

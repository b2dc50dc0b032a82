//! A yardstick, not renderer code: how fast could the Cornell box go if the path loop carried
//! nothing the box does not need, and what would running eight paths in SIMD lanes add to that?
//!
//! `cargo bench -p tessera-benches --bench lean_path [-- RES SPP]` (defaults 128 and 64) loads
//! `scenes/cbox.xml` (box filter) and renders it ten ways (nine without AVX2), one thread each,
//! best of five alternating rounds (`LEAN_ONLY=J` renders only the J-th, once, for callgrind and
//! cachegrind):
//! - `tessera`: the renderer itself (`tessera::render::render`, `path` integrator, the
//!   `independent` sampler);
//! - `lean x1`: a path tracer written for this scene class only (every BSDF diffuse, every
//!   shape a triangle mesh, one mesh area light), with the same estimator: next-event
//!   estimation and BSDF sampling joined by the power heuristic, Russian roulette from depth 5
//!   with Mitsuba's survival probability, max_depth 8. It uses Tessera's own BVH and ray casts
//!   (`Scene::intersect_hit`, `Scene::occluded`), so only the work around them differs: flat
//!   per-primitive tables instead of hit records, no BSDF or emitter dispatch, a small hash
//!   generator instead of a sampler, fixed ray offsets (1e-4) instead of error bounds;
//! - `lean x8`: the same loop over eight paths at a time in structure-of-arrays lanes (a lane
//!   whose path ends starts the next sample), the arithmetic written as loops over the lanes for
//!   the compiler to vectorise; ray casts stay one ray at a time;
//! - `lean x2` and `lean x4` (printed last): the same loop over two and four paths, which
//!   interleaves their stages. Each path is one chain of dependent work; chains side by side
//!   would let the processor overlap them, if waiting on one chain were what limits it;
//! - `tessera zsobol` and `lean x1 zsobol`: the same with the `zsobol` sampler (the lean loop
//!   draws from Tessera's `ZSobolPixel` at the renderer's dimensions, keeping a pixel's cache
//!   while it takes the pixel's samples and telling it their run, as the renderer's workers do);
//! - `lean x1 zsobol robust`: the lean loop with the renderer's robustness instead of fixed
//!   offsets: hit points and light points interpolated from the triangle's corners with their
//!   error bounds, and every ray origin and shadow-ray end moved off its surface by
//!   `offset_ray_origin`, as `Interaction::spawn_ray` and `spawn_ray_to` do: an estimate of what
//!   a loop specialised to this scene class could gain while keeping the renderer's guarantees.
//! - `lean x8 zsobol in step` (printed last; `lean_path/in_step.rs`): the robust zsobol loop over
//!   the eight samples of an aligned group at a time, all at the same bounce, as a wavefront
//!   renderer's lanes: each stage a loop over eight lanes for the compiler to vectorise, the
//!   casts one ray at a time. Same operations in the same order, so the same image as
//!   `lean x1 zsobol robust`.
//! - `lean x8 zsobol avx2` (printed last; `lean_path/in_step_avx2.rs`, only in builds with AVX2
//!   enabled, such as `-C target-cpu=native`): the in-step loop with every stage between the casts
//!   written by hand for eight lanes per AVX instruction (`lean_path/f8.rs`), same operations in
//!   the same order, so again the image of `lean x1 zsobol robust` (checked).
//!
//! Each image's relMSE against `scenes/refs/cbox_RESxRES_mitsuba.exr` is printed beside its
//! speed, so a lean loop that got fast by being wrong would show it. Build with `RUSTFLAGS="-C
//! target-cpu=native"` to let the lanes use AVX2 or AVX-512 throughout.
// Lane code indexes several structure-of-arrays fields by the same lane and channel.
#![allow(clippy::needless_range_loop)]
use glam::{Vec2, Vec3};
use std::path::Path;
use std::time::Instant;
use tessera::render::{render, RenderOptions};
use tessera_core::bsdf::Bsdf;
use tessera_core::emitter::Emitter;
use tessera_core::geometry::{interpolate_point, Prim, ShapeKind, SHADOW_EPSILON};
use tessera_core::integrator::Integrator;
use tessera_core::math::{offset_ray_origin, Norm, Ray};
use tessera_core::render::RenderJob;
use tessera_core::sampling::zsobol::{log2_spp_for, to_unit};
use tessera_core::sampling::{dimension_of, Sampler, SamplerKind, Stage, ZSobolPixel};
use tessera_core::scene::Scene;
use tessera_core::texture::Texture;
use tessera_scene::load_scene;

#[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
#[path = "lean_path/f8.rs"]
mod f8;
#[path = "lean_path/in_step.rs"]
mod in_step;
#[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
#[path = "lean_path/in_step_avx2.rs"]
mod in_step_avx2;

const MAX_DEPTH: u32 = 8;
const RR_DEPTH: u32 = 5;
const OFFSET: f32 = 1e-4;
const INV_PI: f32 = std::f32::consts::FRAC_1_PI;

/// The scene as flat tables indexed by primitive (BVH order), plus the light's triangles.
struct Tables {
    normal: Vec<[f32; 3]>,
    /// Corners of each primitive (for the robust variant's hit points and error bounds).
    corners: Vec<[Vec3; 3]>,
    albedo: Vec<[f32; 3]>,
    emission: Vec<[f32; 3]>,
    light: Vec<LightTriangle>,
    light_area: f32,
    radiance: [f32; 3],
}

/// One triangle of the light.
struct LightTriangle {
    /// The three corners (for the robust variant's light points and error bounds).
    corners: [Vec3; 3],
    corner: [f32; 3],
    edge1: [f32; 3],
    edge2: [f32; 3],
    normal: [f32; 3],
    /// Area of this and the earlier triangles over the light's area.
    cdf: f32,
}

fn albedo_of(b: &Bsdf) -> Result<[f32; 3], String> {
    match b {
        Bsdf::Diffuse(d) => match &d.reflectance {
            Texture::Constant(c) => Ok(c.to_array()),
            _ => Err("a textured reflectance".into()),
        },
        Bsdf::TwoSided(t) => albedo_of(&t.front),
        _ => Err("a BSDF other than diffuse".into()),
    }
}

fn corners(m: &tessera_core::geometry::Mesh, face: usize) -> [Vec3; 3] {
    m.indices[face].map(|i| m.positions[i as usize])
}

impl Tables {
    fn new(scene: &Scene) -> Result<Self, String> {
        let mut t = Tables {
            normal: vec![],
            corners: vec![],
            albedo: vec![],
            emission: vec![],
            light: vec![],
            light_area: 0.0,
            radiance: [0.0; 3],
        };
        for p in &scene.prims {
            let Prim::Triangle { shape, face } = p else {
                return Err("a shape that is not a mesh".into());
            };
            let s = &scene.shapes[*shape as usize];
            let ShapeKind::Mesh(m) = &s.kind else {
                return Err("a shape that is not a mesh".into());
            };
            let [a, b, c] = corners(m, *face as usize);
            t.normal.push((b - a).cross(c - a).unit().to_array());
            t.corners.push([a, b, c]);
            t.albedo.push(albedo_of(&scene.bsdfs[s.bsdf as usize])?);
            t.emission.push(match s.emitter {
                Some(e) => match &scene.emitters[e as usize] {
                    Emitter::Area(a) => a.radiance.to_array(),
                    _ => return Err("an emitter other than area".into()),
                },
                None => [0.0; 3],
            });
        }
        let [Emitter::Area(light)] = scene.emitters.as_slice() else {
            return Err("not exactly one area light".into());
        };
        t.radiance = light.radiance.to_array();
        let ShapeKind::Mesh(m) = &scene.shapes[light.shape as usize].kind else {
            return Err("a light that is not a mesh".into());
        };
        for face in 0..m.indices.len() {
            let [a, b, c] = corners(m, face);
            let cross = (b - a).cross(c - a);
            t.light_area += 0.5 * cross.norm();
            let n = cross.unit().to_array();
            let (e1, e2) = ((b - a).to_array(), (c - a).to_array());
            t.light.push(LightTriangle {
                corners: [a, b, c],
                corner: a.to_array(),
                edge1: e1,
                edge2: e2,
                normal: n,
                cdf: t.light_area,
            });
        }
        for l in &mut t.light {
            l.cdf /= t.light_area;
        }
        Ok(t)
    }
}

/// PCG's output hash of a 32-bit state.
#[inline(always)]
fn hash(x: u32) -> u32 {
    let s = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let w = ((s >> ((s >> 28) + 4)) ^ s).wrapping_mul(277_803_737);
    (w >> 22) ^ w
}

/// `(sin, cos)` of `2 pi u` for `u` in [0, 1): Taylor polynomials of the half angle (|h| <= pi / 2,
/// error below 1e-6), doubled. Branch-free, so it vectorises, which the renderer's
/// `math::sincos_turns` (it calls `libm::sincosf`) does not.
#[inline(always)]
fn sincos_turns_poly(u: f32) -> (f32, f32) {
    let h = (u - (u + 0.5).floor()) * std::f32::consts::PI;
    let h2 = h * h;
    let s =
        h * (1.0 + h2 * (-1.0 / 6.0 + h2 * (1.0 / 120.0 + h2 * (-1.0 / 5040.0 + h2 / 362_880.0))));
    let c = 1.0
        + h2 * (-0.5
            + h2 * (1.0 / 24.0 + h2 * (-1.0 / 720.0 + h2 * (1.0 / 40_320.0 - h2 / 3_628_800.0))));
    (2.0 * s * c, c * c - s * s)
}

/// A cosine-weighted direction about the unit normal `n` from `(u1, u2)` (disk point by radius
/// and angle, frame after Duff et al.), and its cosine to `n`.
#[inline(always)]
fn cosine_bounce(n: [f32; 3], u1: f32, u2: f32) -> ([f32; 3], f32) {
    let r = u1.sqrt();
    let (s, c) = sincos_turns_poly(u2);
    let lz = (1.0 - u1).max(0.0).sqrt();
    let (lx, ly) = (r * c, r * s);
    let [nx, ny, nz] = n;
    let sign = if nz >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + nz);
    let b = nx * ny * a;
    let tan1 = [1.0 + sign * nx * nx * a, sign * b, -sign * nx];
    let tan2 = [b, sign + ny * ny * a, -ny];
    (
        [0, 1, 2].map(|k| tan1[k] * lx + tan2[k] * ly + n[k] * lz),
        lz,
    )
}

/// Where a lane's random numbers come from: the camera's film offset and six values per
/// bounce (light triangle, point on it, direction, roulette).
trait Draws<const N: usize> {
    /// Starts sample `sample` of `pixel` in `lane`; returns the offset within the pixel.
    fn start(&mut self, lane: usize, pixel: u32, sample: u32) -> Vec2;
    /// The six values of bounce `depth` of `lane`'s path.
    fn bounce(&mut self, lane: usize, depth: u32) -> [f32; 6];
}

/// A hash generator per lane (what the lean loop is timed with).
struct HashDraws<const N: usize>([u32; N]);

impl<const N: usize> Draws<N> for HashDraws<N> {
    #[inline(always)]
    fn start(&mut self, lane: usize, pixel: u32, sample: u32) -> Vec2 {
        let r1 = hash(pixel.wrapping_mul(0x9e37_79b9) ^ sample.wrapping_mul(0x85eb_ca6b));
        let r2 = hash(r1);
        self.0[lane] = r2;
        Vec2::new(to_unit(r1), to_unit(r2))
    }
    #[inline(always)]
    fn bounce(&mut self, lane: usize, _depth: u32) -> [f32; 6] {
        let mut r = self.0[lane];
        let u = [0; 6].map(|_| {
            r = hash(r);
            to_unit(r)
        });
        self.0[lane] = r;
        u
    }
}

/// Tessera's zsobol sampler with its per-pixel cache, at the renderer's dimensions.
struct ZSobolDraws<const N: usize> {
    pixels: Vec<ZSobolPixel>,
    /// The pixel each lane's cache serves (`u32::MAX` before the first), so that a lane moves
    /// its cache only when its pixel changes, as the renderer's workers do.
    current: [u32; N],
    index: [u64; N],
    width: u32,
    log2_spp: u32,
    /// Samples per pixel: each pixel's run `0..spp`, told to its cache as the renderer does.
    spp: u64,
}

impl<const N: usize> Draws<N> for ZSobolDraws<N> {
    #[inline(always)]
    fn start(&mut self, lane: usize, pixel: u32, sample: u32) -> Vec2 {
        if self.current[lane] != pixel {
            let (x, y) = (pixel % self.width, pixel / self.width);
            self.pixels[lane].move_to(0, x, y, self.log2_spp);
            self.pixels[lane].set_run(0..self.spp);
            self.current[lane] = pixel;
        }
        self.index[lane] = u64::from(sample);
        self.pixels[lane].sampler(u64::from(sample)).next_2d()
    }
    #[inline(always)]
    fn bounce(&mut self, lane: usize, depth: u32) -> [f32; 6] {
        bounce_draws(&mut self.pixels[lane].sampler(self.index[lane]), depth)
    }
}

/// The six values of bounce `depth` from a sample's sampler, at the renderer's dimensions for
/// the stages (light choice and point, BSDF direction with its component choice skipped,
/// roulette).
#[inline(always)]
fn bounce_draws(s: &mut impl Sampler, depth: u32) -> [f32; 6] {
    s.start_dimension(dimension_of(depth, Stage::Light));
    let (a, b) = (s.next_1d(), s.next_2d());
    s.start_dimension(dimension_of(depth, Stage::Bsdf));
    s.skip_1d();
    let c = s.next_2d();
    s.start_dimension(dimension_of(depth, Stage::Roulette));
    [a, b.x, b.y, c.x, c.y, s.next_1d()]
}

/// Per-lane path state, structure of arrays.
struct Lanes<const N: usize> {
    o: [[f32; N]; 3],
    d: [[f32; N]; 3],
    throughput: [[f32; N]; 3],
    radiance: [[f32; N]; 3],
    prev_pdf: [f32; N],
    depth: [u32; N],
    alive: [bool; N],
    pixel: [u32; N],
}

struct Lean<'a> {
    scene: &'a Scene,
    t: Tables,
    width: u32,
    spp: u32,
}

impl Lean<'_> {
    fn camera_ray(&self, pixel: u32, offset: Vec2) -> Ray {
        let corner = Vec2::new((pixel % self.width) as f32, (pixel / self.width) as f32);
        self.scene.camera.generate_ray(corner + offset)
    }

    /// Renders every pixel's `spp` samples `N` paths at a time; returns the pixel sums.
    #[inline(never)]
    fn render<const N: usize, const ROBUST: bool>(
        &self,
        pixels: u32,
        draws: &mut impl Draws<N>,
    ) -> Vec<[f32; 3]> {
        let mut film = vec![[0f32; 3]; pixels as usize];
        let total = pixels * self.spp;
        let mut next = 0u32;
        let mut l = Lanes::<N> {
            o: [[0.0; N]; 3],
            d: [[0.0; N]; 3],
            throughput: [[0.0; N]; 3],
            radiance: [[0.0; N]; 3],
            prev_pdf: [0.0; N],
            depth: [0; N],
            alive: [false; N],
            pixel: [0; N],
        };
        let t = &self.t;
        loop {
            // Lanes whose path ended start the next sample.
            for i in 0..N {
                if !l.alive[i] && next < total {
                    let (pixel, sample) = (next / self.spp, next % self.spp);
                    next += 1;
                    let ray = self.camera_ray(pixel, draws.start(i, pixel, sample));
                    for k in 0..3 {
                        l.o[k][i] = ray.o[k];
                        l.d[k][i] = ray.d[k];
                        l.throughput[k][i] = 1.0;
                        l.radiance[k][i] = 0.0;
                    }
                    (l.prev_pdf[i], l.depth[i]) = (0.0, 0);
                    (l.alive[i], l.pixel[i]) = (true, pixel);
                }
            }
            if !l.alive.iter().any(|&a| a) {
                break;
            }
            // Closest hits, one ray at a time, and the hit primitives' table rows.
            let mut dist = [0f32; N];
            let mut prim = [0usize; N];
            let mut bary = [Vec2::ZERO; N];
            let mut hit = [false; N];
            let mut n = [[0f32; N]; 3];
            let mut albedo = [[0f32; N]; 3];
            let mut emission = [[0f32; N]; 3];
            for i in 0..N {
                if !l.alive[i] {
                    continue;
                }
                let ray = Ray {
                    o: Vec3::new(l.o[0][i], l.o[1][i], l.o[2][i]),
                    d: Vec3::new(l.d[0][i], l.d[1][i], l.d[2][i]),
                    t_max: f32::INFINITY,
                };
                if let Some(h) = self.scene.intersect_hit(&ray) {
                    let p = h.prim as usize;
                    (hit[i], dist[i]) = (true, h.t);
                    (prim[i], bary[i]) = (p, h.uv);
                    for k in 0..3 {
                        n[k][i] = t.normal[p][k];
                        albedo[k][i] = t.albedo[p][k];
                        emission[k][i] = t.emission[p][k];
                    }
                }
            }
            let mut u = [[0f32; N]; 6];
            for i in 0..N {
                if l.alive[i] {
                    let v = draws.bounce(i, l.depth[i]);
                    for (uk, v) in u.iter_mut().zip(v) {
                        uk[i] = v;
                    }
                }
            }
            // Emission found by the ray, and one emitter sample.
            let mut p = [[0f32; N]; 3];
            let mut p_err = [Vec3::ZERO; N];
            let mut shadow_o = [Vec3::ZERO; N];
            let mut shadow_d = [Vec3::ZERO; N];
            let mut shadow_t = [0f32; N];
            let mut light_value = [[0f32; N]; 3];
            let mut go_on = [false; N];
            for i in 0..N {
                let live = l.alive[i] && hit[i];
                if ROBUST && live {
                    // The renderer's hit point: barycentric interpolation and its error bound.
                    let [a, b, c] = t.corners[prim[i]];
                    let (q, e) = interpolate_point(a, b, c, bary[i].x, bary[i].y);
                    for k in 0..3 {
                        p[k][i] = q[k];
                    }
                    p_err[i] = e;
                } else {
                    for k in 0..3 {
                        p[k][i] = l.o[k][i] + l.d[k][i] * dist[i];
                    }
                }
                let dn = n[0][i] * l.d[0][i] + n[1][i] * l.d[1][i] + n[2][i] * l.d[2][i];
                let cos_at_light = -dn;
                let flip = if dn > 0.0 { -1.0 } else { 1.0 };
                for nk in n.iter_mut() {
                    nk[i] *= flip;
                }
                let emits = live
                    && emission[0][i] + emission[1][i] + emission[2][i] > 0.0
                    && cos_at_light > 0.0;
                let light_pdf = dist[i] * dist[i] / (cos_at_light * t.light_area);
                let w = if l.depth[i] == 0 {
                    1.0
                } else {
                    let b = l.prev_pdf[i] * l.prev_pdf[i];
                    b / (b + light_pdf * light_pdf)
                };
                for k in 0..3 {
                    let add = l.throughput[k][i] * emission[k][i] * w;
                    l.radiance[k][i] += if emits { add } else { 0.0 };
                }
                go_on[i] = live && l.depth[i] + 1 < MAX_DEPTH;
                let tri = if t.light.len() > 1 && u[0][i] >= t.light[0].cdf {
                    &t.light[1]
                } else {
                    &t.light[0]
                };
                let su = u[1][i].sqrt();
                let (b1, b2) = (1.0 - su, u[2][i] * su);
                let mut wo = [0f32; 3];
                let (lp, lp_err) = if ROBUST {
                    let [a, b, c] = tri.corners;
                    interpolate_point(a, b, c, b1, b2)
                } else {
                    let mut q = Vec3::ZERO;
                    for k in 0..3 {
                        q[k] = tri.corner[k] + tri.edge1[k] * b1 + tri.edge2[k] * b2;
                    }
                    (q, Vec3::ZERO)
                };
                for (k, w) in wo.iter_mut().enumerate() {
                    *w = lp[k] - p[k][i];
                }
                let d2 = wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2];
                let d = d2.sqrt();
                for w in wo.iter_mut() {
                    *w /= d;
                }
                let cos_l =
                    -(tri.normal[0] * wo[0] + tri.normal[1] * wo[1] + tri.normal[2] * wo[2]);
                let cos_s = n[0][i] * wo[0] + n[1][i] * wo[1] + n[2][i] * wo[2];
                let light_pdf = d2 / (cos_l * t.light_area);
                let bsdf_pdf = cos_s * INV_PI;
                let w = light_pdf * light_pdf / (light_pdf * light_pdf + bsdf_pdf * bsdf_pdf);
                let ok = go_on[i] && cos_l > 0.0 && cos_s > 0.0;
                let pi = Vec3::new(p[0][i], p[1][i], p[2][i]);
                let ni = Vec3::new(n[0][i], n[1][i], n[2][i]);
                if !ok {
                    shadow_t[i] = -1.0;
                } else if ROBUST {
                    // The renderer's shadow segment: both ends offset by their error bounds.
                    let tn = Vec3::from(tri.normal);
                    let target = offset_ray_origin(lp, lp_err, tn, pi - lp);
                    let o = offset_ray_origin(pi, p_err[i], ni, target - pi);
                    (shadow_o[i], shadow_d[i], shadow_t[i]) = (o, target - o, 1.0 - SHADOW_EPSILON);
                } else {
                    shadow_o[i] = pi + ni * OFFSET;
                    shadow_d[i] = Vec3::from(wo);
                    shadow_t[i] = d * (1.0 - OFFSET);
                }
                for k in 0..3 {
                    light_value[k][i] =
                        l.throughput[k][i] * albedo[k][i] * INV_PI * cos_s * t.radiance[k] * w
                            / light_pdf;
                }
            }
            // Shadow rays, one at a time.
            for i in 0..N {
                let shadow = Ray {
                    o: shadow_o[i],
                    d: shadow_d[i],
                    t_max: shadow_t[i],
                };
                if shadow_t[i] > 0.0 && !self.scene.occluded(&shadow) {
                    for k in 0..3 {
                        l.radiance[k][i] += light_value[k][i];
                    }
                }
            }
            // Cosine-weighted bounce (Duff et al.'s frame), then Russian roulette.
            for i in 0..N {
                let (dir, lz) = cosine_bounce([n[0][i], n[1][i], n[2][i]], u[3][i], u[4][i]);
                for k in 0..3 {
                    l.d[k][i] = dir[k];
                    l.throughput[k][i] *= albedo[k][i];
                }
                let pi = Vec3::new(p[0][i], p[1][i], p[2][i]);
                let ni = Vec3::new(n[0][i], n[1][i], n[2][i]);
                let o = if ROBUST {
                    let d = Vec3::new(l.d[0][i], l.d[1][i], l.d[2][i]);
                    offset_ray_origin(pi, p_err[i], ni, d)
                } else {
                    pi + ni * OFFSET
                };
                for k in 0..3 {
                    l.o[k][i] = o[k];
                }
                l.prev_pdf[i] = lz * INV_PI;
                l.depth[i] += 1;
                let mut keep = go_on[i] && lz > 0.0;
                if l.depth[i] >= RR_DEPTH {
                    let q = l.throughput[0][i]
                        .max(l.throughput[1][i])
                        .max(l.throughput[2][i])
                        .min(0.95);
                    keep &= u[5][i] < q;
                    for k in 0..3 {
                        l.throughput[k][i] /= q;
                    }
                }
                hit[i] = keep;
            }
            // Ended paths go to the film.
            for i in 0..N {
                if l.alive[i] && !hit[i] {
                    for k in 0..3 {
                        film[l.pixel[i] as usize][k] += l.radiance[k][i];
                    }
                    l.alive[i] = false;
                }
            }
        }
        film
    }
}

fn main() {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (res, spp) = (
        args.first().copied().unwrap_or(128),
        args.get(1).copied().unwrap_or(64),
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let defines =
        [("res", res.to_string()), ("rfilter", "box".to_string())].map(|(k, v)| (k.to_string(), v));
    let mut loaded = load_scene(&root.join("scenes/cbox.xml"), &defines).expect("cbox loads");
    loaded
        .set_sampler(Some("independent"), u64::from(spp))
        .expect("sampler");
    let reference = tessera::image_io::read_image(
        &root.join(format!("scenes/refs/cbox_{res}x{res}_mitsuba.exr")),
    )
    .ok();
    let scene = &loaded.scene;
    let mut zsobol_scene = scene.clone();
    zsobol_scene.sampler = SamplerKind::from_name("zsobol", u64::from(spp)).expect("zsobol");
    let lean = Lean {
        scene,
        t: Tables::new(scene).expect("a diffuse, triangle-only scene with one mesh light"),
        width: res,
        spp,
    };
    let integrator: &Integrator = &loaded.integrator;
    let opts = RenderOptions::default();
    let samples = 0..u64::from(spp);
    let job = RenderJob::new(scene, integrator, 0);
    let zsobol_job = RenderJob::new(&zsobol_scene, integrator, 0);
    let pixels = res * res;
    let names = [
        "tessera",
        "lean x1",
        "lean x8",
        "tessera zsobol",
        "lean x1 zsobol",
        "lean x1 zsobol robust",
        "lean x2",
        "lean x4",
        "lean x8 zsobol in step",
        "lean x8 zsobol avx2",
    ];
    let mut best = [f64::INFINITY; 10];
    let mut images: [Vec<[f32; 3]>; 10] = Default::default();
    let zsobol = || ZSobolDraws::<1> {
        pixels: vec![ZSobolPixel::new(0, 0, 0, 0)],
        current: [u32::MAX],
        index: [0],
        width: res,
        log2_spp: log2_spp_for(u64::from(spp)),
        spp: u64::from(spp),
    };
    // `LEAN_ONLY=J`: one round of variant J alone (0-9, in the order of `names`).
    let only: Option<usize> = std::env::var("LEAN_ONLY")
        .ok()
        .map(|j| j.parse().expect("LEAN_ONLY is a variant index"));
    for _round in 0..if only.is_some() { 1 } else { 5 } {
        for (j, best) in best.iter_mut().enumerate() {
            if only.is_some_and(|o| o != j) {
                continue;
            }
            let avx2 = cfg!(all(target_arch = "x86_64", target_feature = "avx2"));
            if j == 9 && !avx2 {
                continue;
            }
            let start = Instant::now();
            let img = match j {
                0 => render(&job, samples.clone(), &opts, &mut |_, _| {}).rgb(),
                1 => lean.render::<1, false>(pixels, &mut HashDraws([0; 1])),
                2 => lean.render::<8, false>(pixels, &mut HashDraws([0; 8])),
                3 => render(&zsobol_job, samples.clone(), &opts, &mut |_, _| {}).rgb(),
                4 => lean.render::<1, false>(pixels, &mut zsobol()),
                5 => lean.render::<1, true>(pixels, &mut zsobol()),
                6 => lean.render::<2, false>(pixels, &mut HashDraws([0; 2])),
                7 => lean.render::<4, false>(pixels, &mut HashDraws([0; 4])),
                8 => lean.render_in_step(pixels),
                #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
                _ => lean.render_in_step_avx2(pixels),
                #[cfg(not(all(target_arch = "x86_64", target_feature = "avx2")))]
                _ => unreachable!("skipped above"),
            };
            *best = best.min(start.elapsed().as_secs_f64());
            images[j] = img;
        }
    }
    // The lean loops return pixel sums; the renderer returns means.
    for (img, _) in images
        .iter_mut()
        .zip(names)
        .filter(|(_, n)| n.starts_with("lean"))
    {
        for p in img.iter_mut() {
            p.iter_mut().for_each(|v| *v /= spp as f32);
        }
    }
    // Both in-step variants must give the bits of the loop they rearrange.
    for j in [8, 9] {
        if !images[5].is_empty() && !images[j].is_empty() {
            let same = images[5]
                .iter()
                .flatten()
                .map(|v| v.to_bits())
                .eq(images[j].iter().flatten().map(|v| v.to_bits()));
            assert!(
                same,
                "{} changed the image of lean x1 zsobol robust",
                names[j]
            );
        }
    }
    println!("cbox {res}x{res}, {spp} spp, 1 thread, best of 5");
    for j in (0..10).filter(|&j| only.is_none_or(|o| o == j) && !images[j].is_empty()) {
        let rate = f64::from(pixels * spp) / best[j] / 1e6;
        let err = reference
            .as_ref()
            .map_or(String::from("no reference"), |r| {
                format!(
                    "relMSE {:.3e}",
                    tessera_lab::bench::errors(&images[j], &r.data).relmse
                )
            });
        println!(
            "  {:<22} {:7.3} s {:6.3} M samples/s ({:.2}x tessera)  {err}",
            names[j],
            best[j],
            rate,
            best[0] / best[j]
        );
    }
}

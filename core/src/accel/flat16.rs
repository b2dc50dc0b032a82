//! Casts in the smallest scenes with AVX-512: every triangle of a one-node hierarchy tested in
//! sixteen-lane passes (one of the crate's few modules allowed `unsafe`).
//!
//! A scene whose hierarchy is a single 8-wide node of leaves holding at most
//! [`MAX_TRIANGLES`] triangles and nothing else (the Cornell box: 32 triangles in 8 leaves) is
//! walked by [`super::Bvh8`]'s root walk as one box test, then the hit leaves nearest first, each
//! leaf's triangles in blocks of four. With AVX-512 all the triangles fit in two registers' worth
//! of lanes, so [`Flat16`] tests them all at once instead: the root's box test, one or two
//! sixteen-lane triangle tests (the operations of [`super::tri4::test4_sse`], lane by lane, in the
//! same order, so each lane's hit, distance and barycentrics have the same bits), then a
//! reduction to the nearest hit. No leaf order, stack or per-lane loop.
//!
//! The answer must be the general walk's, bit for bit, including which triangle wins. Each
//! method returns `None` ("undecided": the caller runs the general walk) unless these hold:
//! - No triangle of a hit leaf is left to the scalar test (an edge function exactly zero).
//! - Closest hit: exactly one lane holds the least distance `t_m` among the hits in hit leaves.
//!   Let `t_2` be the next least hit distance (or the ray's `t_max`). The walk visits the
//!   winner's leaf unless that leaf is entered beyond the closest hit so far, which is never
//!   below `t_2`. It accepts the winner unless the re-check against the lowered `t_max`
//!   ([`super::tri4::Lanes::accepts`]) fails, which is monotone in `t_max`. So the fast answer
//!   is taken only when the leaf's entry distance is at most `t_2` and the winner passes the
//!   re-check at `t_2`. Then the walk ends on the same lane, with the same bits. Ties and the
//!   rare rounding cases go to the walk.
//! - Any hit: a lane that hits in a hit leaf is what the walk would find (it visits every hit
//!   leaf until a hit).
//!
//! The CPU is asked once per scene build ([`Avx512::detect`]); without AVX-512 (or on other
//! targets) scenes have no `Flat16` and cast as before. `tests/tests/flat16.rs` compares the
//! answers with the general walk's and counts how often the fast path decides: every one of
//! 80,000 rays inside the Cornell box; about half of the rays aimed at its triangles' shared
//! corners and edges (ties). Its nearly coincident triangles reach the entry-distance condition;
//! no test ray has reached the re-check condition, which needs two hits one rounding apart.
//!
//! Why `unsafe` here: AVX-512 intrinsics are callable only from code compiled with the feature,
//! and calling such code from ordinary code is `unsafe`; the [`Avx512`] token proves the CPU has
//! it. Each block says why it is sound.
#![allow(unsafe_code)]

use super::simd::RayPre;
use super::simd8::Boxes8;
use super::tri4::Ray4;
use super::{Bvh8, TriBlocks};
use crate::geometry::Hit;
use crate::math::Ray;
use glam::Vec2;

/// The most triangles a scene may hold for [`Flat16`]: two sixteen-lane tests.
pub const MAX_TRIANGLES: usize = 32;

/// Sixteen triangles' corners in SoA layout, `v[3 * corner + axis][lane]` (NaN in unused lanes).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Group16 {
    v: [[f32; 16]; 9],
}

/// All triangles of a one-node scene, for sixteen-lane tests (see the module header).
#[derive(Clone, Debug)]
pub struct Flat16 {
    /// The root node's child boxes (its leaves'), and which lanes are used.
    boxes: Boxes8,
    used: u32,
    /// One or two groups.
    groups: [Group16; 2],
    two: bool,
    /// Per lane (`16 * group + lane`): primitive index and the root lane of its leaf.
    prim: [u32; MAX_TRIANGLES],
    leaf: [u8; MAX_TRIANGLES],
    /// For each set of hit leaves (bit `i`: root lane `i`), the lanes of their triangles.
    lanes_of: [u32; 256],
    /// Proof that the CPU runs AVX-512F (what makes the `unsafe` calls sound).
    #[allow(dead_code)]
    token: Avx512,
}

/// Proof that this CPU runs AVX-512F code (with AVX2 and POPCNT): only [`Avx512::detect`] makes
/// one, and only when it does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Avx512 {
    _private: (),
}

impl Avx512 {
    /// Asks the CPU (CPUID, XGETBV): AVX2, POPCNT and AVX-512F present, and the OS saving the
    /// AVX-512 registers.
    pub fn detect() -> Option<Avx512> {
        super::simd8::Avx2::detect()?;
        #[cfg(target_arch = "x86_64")]
        {
            use core::arch::x86_64::{__cpuid_count, _xgetbv};
            // Avx2::detect checked CPUID leaf 7 exists and OSXSAVE is set.
            let avx512f = __cpuid_count(7, 0).ebx & (1 << 16) != 0;
            // SAFETY: OSXSAVE was checked by `Avx2::detect`, so XGETBV is executable and XCR0
            // exists.
            let xcr0 = unsafe { _xgetbv(0) };
            // XMM, YMM, opmask, upper halves of ZMM0-15, ZMM16-31 state all enabled.
            let os = xcr0 & 0xE6 == 0xE6;
            (avx512f && os).then_some(Avx512 { _private: () })
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            None
        }
    }
}

impl Flat16 {
    /// The sixteen-lane form of a scene, when it qualifies: a hierarchy of one node whose
    /// children are all leaves, at most [`MAX_TRIANGLES`] primitives, all triangles; and a CPU
    /// with AVX-512 (`token`).
    pub fn build(bvh: &Bvh8, blocks: &TriBlocks, token: Option<Avx512>) -> Option<Flat16> {
        let token = token?;
        let [node] = bvh.nodes.as_slice() else {
            return None;
        };
        if node.leaves & node.used != node.used {
            return None;
        }
        let empty = Group16 {
            v: [[f32::NAN; 16]; 9],
        };
        let mut flat = Flat16 {
            boxes: node.boxes,
            used: node.used,
            groups: [empty; 2],
            two: false,
            prim: [0; MAX_TRIANGLES],
            leaf: [0; MAX_TRIANGLES],
            lanes_of: [0; 256],
            token,
        };
        let mut leaf_lanes = [0u32; 8];
        let mut n = 0;
        for (c, lanes) in leaf_lanes.iter_mut().enumerate() {
            if node.used & (1 << c) == 0 {
                continue;
            }
            let (first, count) = (node.child[c] as usize, usize::from(node.count[c]));
            for i in 0..count {
                let blk = &blocks.blocks[first + i / 4];
                let lane = i % 4;
                if blk.v[0][lane].is_nan() || n == MAX_TRIANGLES {
                    // Not a triangle, or too many.
                    return None;
                }
                let g = &mut flat.groups[n / 16];
                for row in 0..9 {
                    g.v[row][n % 16] = blk.v[row][lane];
                }
                flat.prim[n] = blk.first + lane as u32;
                flat.leaf[n] = c as u8;
                *lanes |= 1 << n;
                n += 1;
            }
        }
        flat.two = n > 16;
        for (set, lanes) in flat.lanes_of.iter_mut().enumerate() {
            *lanes = (0..8)
                .filter(|c| set & (1 << c) != 0)
                .fold(0, |m, c| m | leaf_lanes[c]);
        }
        Some(flat)
    }

    /// The closest hit within `(0, ray.t_max)`, `r4` being the ray's triangle setup: `Some` with
    /// the general walk's answer, or `None` where this test cannot vouch for it (see the module
    /// header).
    #[inline]
    pub fn closest(&self, ray: &Ray, r4: &Ray4) -> Option<Option<Hit>> {
        #[cfg(target_arch = "x86_64")]
        {
            // SAFETY: a `Flat16` holds an `Avx512` token, which exists only when the CPU runs
            // AVX-512F, AVX2 and POPCNT code.
            unsafe { self.closest_avx512(ray, r4) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = (ray, r4);
            None
        }
    }

    /// Whether anything blocks the ray within `(0, ray.t_max)`: `Some` with the general walk's
    /// answer, or `None` where a triangle is left to the scalar test.
    #[inline]
    pub fn any(&self, ray: &Ray, r4: &Ray4) -> Option<bool> {
        #[cfg(target_arch = "x86_64")]
        {
            // SAFETY: as in `closest`.
            unsafe { self.any_avx512(ray, r4) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = (ray, r4);
            None
        }
    }

    /// The root's box test: the hit leaves' lanes and the leaves' entry distances.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx2,popcnt")]
    #[inline]
    fn leaves_hit(&self, ray: &Ray) -> (u32, [f32; 8]) {
        let pre = RayPre::new(ray);
        let (mask, t_near) = super::simd8::hit8_avx2(&self.boxes, &pre, ray.t_max);
        (self.lanes_of[(mask & self.used) as usize], t_near)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx2,popcnt")]
    fn closest_avx512(&self, ray: &Ray, r4: &Ray4) -> Option<Option<Hit>> {
        use core::arch::x86_64::*;
        let (lanes, t_near) = self.leaves_hit(ray);
        if lanes == 0 {
            return Some(None);
        }
        let a = test16(&self.groups[0], r4, ray.t_max);
        let b = if self.two {
            test16(&self.groups[1], r4, ray.t_max)
        } else {
            Out16::NONE
        };
        if (a.fallback as u32 | (b.fallback as u32) << 16) & lanes != 0 {
            return None;
        }
        let hits = (a.hit as u32 | (b.hit as u32) << 16) & lanes;
        if hits == 0 {
            return Some(None);
        }
        let inf = _mm512_set1_ps(f32::INFINITY);
        // Hit distances, other lanes at infinity (hits are finite and positive).
        let ta = _mm512_mask_blend_ps(hits as u16, inf, a.t);
        let tb = _mm512_mask_blend_ps((hits >> 16) as u16, inf, b.t);
        let t_min = _mm512_reduce_min_ps(_mm512_min_ps(ta, tb));
        let at_min = _mm512_set1_ps(t_min);
        let ties = _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(ta, at_min) as u32
            | (_mm512_cmp_ps_mask::<_CMP_EQ_OQ>(tb, at_min) as u32) << 16;
        if ties.count_ones() != 1 {
            return None;
        }
        let m = ties.trailing_zeros() as usize;
        let rest = hits & !ties;
        let t2 = if rest == 0 {
            ray.t_max
        } else {
            let ta = _mm512_mask_blend_ps(rest as u16, inf, a.t);
            let tb = _mm512_mask_blend_ps((rest >> 16) as u16, inf, b.t);
            _mm512_reduce_min_ps(_mm512_min_ps(ta, tb))
        };
        if t_near[usize::from(self.leaf[m])] > t2 {
            return None;
        }
        let o = if m < 16 { &a } else { &b };
        let l = m % 16;
        let lane = |x: __m512| {
            let mut v = [0.0f32; 16];
            // SAFETY: writes the sixteen f32s of the local `v` (`storeu` needs no alignment).
            unsafe { _mm512_storeu_ps(v.as_mut_ptr(), x) };
            v[l]
        };
        let (ts, det) = (lane(o.t_scaled), lane(o.det));
        // The general walk's re-check at a lowered `t_max` (`Lanes::accepts`) at `t2`.
        let beyond = if det < 0.0 {
            ts < t2 * det
        } else {
            ts > t2 * det
        };
        if beyond || t_min >= t2 {
            return None;
        }
        // `1 / det` and the products are the vector test's operations, so the same bits.
        let inv_det = 1.0 / det;
        Some(Some(Hit {
            t: t_min,
            prim: self.prim[m],
            uv: Vec2::new(lane(o.e1) * inv_det, lane(o.e2) * inv_det),
        }))
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx2,popcnt")]
    fn any_avx512(&self, ray: &Ray, r4: &Ray4) -> Option<bool> {
        let (lanes, _) = self.leaves_hit(ray);
        if lanes == 0 {
            return Some(false);
        }
        let mut undecided = false;
        for (g, group) in self.groups[..1 + usize::from(self.two)].iter().enumerate() {
            let want = (lanes >> (16 * g)) as u16;
            if want == 0 {
                continue;
            }
            let o = test16(group, r4, ray.t_max);
            if o.hit & want != 0 {
                return Some(true);
            }
            undecided |= o.fallback & want != 0;
        }
        (!undecided).then_some(false)
    }
}

/// What a sixteen-lane test found: masks by lane, and the values the closest hit needs
/// (meaningful in `hit` lanes).
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
struct Out16 {
    hit: u16,
    fallback: u16,
    t: core::arch::x86_64::__m512,
    t_scaled: core::arch::x86_64::__m512,
    det: core::arch::x86_64::__m512,
    e1: core::arch::x86_64::__m512,
    e2: core::arch::x86_64::__m512,
}

#[cfg(target_arch = "x86_64")]
impl Out16 {
    /// No lane hit or undecided.
    const NONE: Out16 = {
        let z = unsafe_zero();
        Out16 {
            hit: 0,
            fallback: 0,
            t: z,
            t_scaled: z,
            det: z,
            e1: z,
            e2: z,
        }
    };
}

/// A zero vector as a constant.
#[cfg(target_arch = "x86_64")]
const fn unsafe_zero() -> core::arch::x86_64::__m512 {
    // SAFETY: `__m512` is sixteen f32s with no invalid bit patterns; all-zero bits are 0.0.
    unsafe { core::mem::transmute::<[f32; 16], core::arch::x86_64::__m512>([0.0; 16]) }
}

/// The watertight test on sixteen lanes: [`super::tri4::test4_sse`]'s operations in the same
/// order, each SSE comparison replaced by the AVX-512 compare with the same predicate (NaN
/// included: `cmpneqps` is `NEQ_UQ`, the others ordered).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
fn test16(g: &Group16, r: &Ray4, t_max: f32) -> Out16 {
    use crate::math::gamma;
    use core::arch::x86_64::*;
    let [kx, ky, kz] = r.k;
    let zero = _mm512_setzero_ps();
    // SAFETY: reads row `g.v[i]` (`i < 9`, bounds-checked), sixteen initialised f32s borrowed for
    // the call (`loadu` needs no alignment).
    let row = |i: usize| unsafe { _mm512_loadu_ps(g.v[i].as_ptr()) };
    let o = |k: usize| _mm512_set1_ps(r.o[k]);
    let (okx, oky, okz) = (o(kx), o(ky), o(kz));
    let (sx, sy, sz) = (
        _mm512_set1_ps(r.s[0]),
        _mm512_set1_ps(r.s[1]),
        _mm512_set1_ps(r.s[2]),
    );
    let corner = |c: usize| {
        let x = _mm512_sub_ps(row(3 * c + kx), okx);
        let y = _mm512_sub_ps(row(3 * c + ky), oky);
        let z = _mm512_sub_ps(row(3 * c + kz), okz);
        (
            _mm512_add_ps(x, _mm512_mul_ps(sx, z)),
            _mm512_add_ps(y, _mm512_mul_ps(sy, z)),
            z,
        )
    };
    let (ax, ay, az) = corner(0);
    let (bx, by, bz) = corner(1);
    let (cx, cy, cz) = corner(2);
    let e0 = _mm512_sub_ps(_mm512_mul_ps(bx, cy), _mm512_mul_ps(by, cx));
    let e1 = _mm512_sub_ps(_mm512_mul_ps(cx, ay), _mm512_mul_ps(cy, ax));
    let e2 = _mm512_sub_ps(_mm512_mul_ps(ax, by), _mm512_mul_ps(ay, bx));
    let eq0 = |x: __m512| _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(x, zero);
    let lt0 = |x: __m512| _mm512_cmp_ps_mask::<_CMP_LT_OS>(x, zero);
    let gt0 = |x: __m512| _mm512_cmp_ps_mask::<_CMP_GT_OS>(x, zero);
    let p0x = row(0);
    let fallback = eq0(e0) | eq0(e1) | eq0(e2) | _mm512_cmp_ps_mask::<_CMP_UNORD_Q>(p0x, p0x);
    let mixed = (lt0(e0) | lt0(e1) | lt0(e2)) & (gt0(e0) | gt0(e1) | gt0(e2));
    let undecided = mixed | fallback;
    let mut out = Out16 {
        fallback,
        ..Out16::NONE
    };
    // Most groups stop here: every lane is missed by the edge test or left to the scalar one.
    if undecided == 0xFFFF {
        return out;
    }
    let abs = |x: __m512| _mm512_abs_ps(x);
    let mx = |a: __m512, b: __m512| _mm512_max_ps(a, b);
    let det = _mm512_add_ps(_mm512_add_ps(e0, e1), e2);
    let det_ok = _mm512_cmp_ps_mask::<_CMP_NEQ_UQ>(det, zero)
        & _mm512_cmp_ps_mask::<_CMP_LT_OS>(abs(det), _mm512_set1_ps(f32::INFINITY));
    let (szx, szy, szz) = (
        _mm512_mul_ps(az, sz),
        _mm512_mul_ps(bz, sz),
        _mm512_mul_ps(cz, sz),
    );
    let t_scaled = _mm512_add_ps(
        _mm512_add_ps(_mm512_mul_ps(e0, szx), _mm512_mul_ps(e1, szy)),
        _mm512_mul_ps(e2, szz),
    );
    let tmax = _mm512_set1_ps(t_max);
    let tmd = _mm512_mul_ps(tmax, det);
    let neg_bad = lt0(det)
        & (_mm512_cmp_ps_mask::<_CMP_GE_OS>(t_scaled, zero)
            | _mm512_cmp_ps_mask::<_CMP_LT_OS>(t_scaled, tmd));
    let pos_bad = gt0(det)
        & (_mm512_cmp_ps_mask::<_CMP_LE_OS>(t_scaled, zero)
            | _mm512_cmp_ps_mask::<_CMP_GT_OS>(t_scaled, tmd));
    let inv_det = _mm512_div_ps(_mm512_set1_ps(1.0), det);
    let t = _mm512_mul_ps(t_scaled, inv_det);
    let pass =
        !(undecided | neg_bad | pos_bad) & det_ok & _mm512_cmp_ps_mask::<_CMP_LT_OS>(t, tmax);
    // Groups whose lanes all lie outside (0, t_max) stop here.
    if pass == 0 {
        return out;
    }
    // The conservative lower bound on t, as the scalar test computes it.
    let max_z_len = mx(abs(az), mx(abs(bz), abs(cz)));
    let max_zt = mx(abs(szx), mx(abs(szy), abs(szz)));
    let delta_z = _mm512_mul_ps(_mm512_set1_ps(gamma(3)), max_zt);
    let max_xt = mx(abs(ax), mx(abs(bx), abs(cx)));
    let max_yt = mx(abs(ay), mx(abs(by), abs(cy)));
    let g5 = _mm512_set1_ps(gamma(5));
    let delta_x = _mm512_mul_ps(g5, _mm512_add_ps(max_xt, max_z_len));
    let delta_y = _mm512_mul_ps(g5, _mm512_add_ps(max_yt, max_z_len));
    let delta_e = _mm512_mul_ps(
        _mm512_set1_ps(2.0),
        _mm512_add_ps(
            _mm512_add_ps(
                _mm512_mul_ps(_mm512_mul_ps(_mm512_set1_ps(gamma(2)), max_xt), max_yt),
                _mm512_mul_ps(delta_y, max_xt),
            ),
            _mm512_mul_ps(delta_x, max_yt),
        ),
    );
    let max_e = mx(abs(e0), mx(abs(e1), abs(e2)));
    let sum = _mm512_add_ps(
        _mm512_add_ps(
            _mm512_mul_ps(_mm512_mul_ps(_mm512_set1_ps(gamma(3)), max_e), max_zt),
            _mm512_mul_ps(delta_e, max_zt),
        ),
        _mm512_mul_ps(delta_z, max_e),
    );
    let delta_t = _mm512_mul_ps(_mm512_mul_ps(_mm512_set1_ps(3.0), sum), abs(inv_det));
    out.hit = pass & !_mm512_cmp_ps_mask::<_CMP_LE_OS>(t, delta_t);
    out.t = t;
    out.t_scaled = t_scaled;
    out.det = det;
    out.e1 = e1;
    out.e2 = e2;
    out
}

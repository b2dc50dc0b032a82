//! Four watertight ray-triangle tests at once (one of the crate's few modules allowed `unsafe`).
//!
//! A [`Tri4`] block holds the corners of up to four triangles in SoA layout. [`test4`] runs the
//! test of [`crate::geometry::TriRay::intersect`] (Woop, Benthin and Wald 2013) on all four
//! lanes with SSE on x86_64 ([`test4_sse`]) and with a portable loop elsewhere
//! ([`test4_scalar`]). Both perform, per lane, exactly the operations of the scalar test in the
//! same order (IEEE subtraction, multiplication, addition and division; no fused multiply-add;
//! `max` as glam's `max_element` does it, `if a > b { a } else { b }`, which is what `maxps`
//! computes), so a lane reports the same hit or miss, distance and barycentrics, bit for bit, as
//! the scalar test. Lanes the vector code does not decide are flagged `fallback`: an edge
//! function that rounds to exactly zero (the scalar test recomputes those in f64) and lanes
//! holding no triangle (NaN corners: spheres and disks stored in the block); the caller runs the
//! scalar test (or the primitive's own) for those.
//!
//! Why `unsafe` here: the SSE intrinsics are `unsafe fn`s unless the calling function itself is
//! declared `#[target_feature(enable = "sse")]`, and calling such a function from ordinary code
//! is `unsafe` again, even though SSE and SSE2 are part of the x86_64 baseline and statically
//! enabled. The one block below says why it is sound.
#![allow(unsafe_code)]

use crate::geometry::TriRay;
use crate::math::gamma;
use glam::Vec3;

/// Four triangles' corners in SoA layout, `v[3 * corner + axis][lane]`, and the index of the
/// primitive in lane 0 (lane `i` holds primitive `first + i`). 148 bytes: 37 per triangle when
/// full. Unused lanes and lanes of primitives that are not triangles hold NaN corners.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Tri4 {
    /// Corner coordinates: row `3 * corner + axis`, one column per lane.
    pub v: [[f32; 4]; 9],
    /// Primitive index of lane 0.
    pub first: u32,
}

impl Tri4 {
    /// A block with no triangle in any lane.
    pub const EMPTY: Tri4 = Tri4 {
        v: [[f32::NAN; 4]; 9],
        first: 0,
    };

    /// Stores a triangle's corners in `lane`.
    pub fn set(&mut self, lane: usize, corners: &[Vec3; 3]) {
        for (c, p) in corners.iter().enumerate() {
            for a in 0..3 {
                self.v[3 * c + a][lane] = p[a];
            }
        }
    }

    /// Lanes holding no triangle (NaN first corner): primitives that are not triangles, and
    /// unused lanes. Bit `i` is lane `i`.
    #[inline(always)]
    pub fn nan_lanes(&self) -> u32 {
        #[cfg(target_arch = "x86_64")]
        {
            use core::arch::x86_64::{_mm_cmpunord_ps, _mm_loadu_ps, _mm_movemask_ps};
            // SAFETY: SSE and SSE2 are in the x86_64 baseline; the load reads the four
            // initialised f32s of `self.v[0]`, borrowed for the call (no alignment needed).
            unsafe {
                let x = _mm_loadu_ps(self.v[0].as_ptr());
                _mm_movemask_ps(_mm_cmpunord_ps(x, x)) as u32
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            (0..4).fold(0, |m, l| m | (u32::from(self.v[0][l].is_nan()) << l))
        }
    }

    /// The corners stored in `lane`.
    #[inline(always)]
    pub fn corners(&self, lane: usize) -> [Vec3; 3] {
        let p = |c: usize| {
            Vec3::new(
                self.v[3 * c][lane],
                self.v[3 * c + 1][lane],
                self.v[3 * c + 2][lane],
            )
        };
        [p(0), p(1), p(2)]
    }
}

/// The per-ray part of the four-lane test: origin, axis permutation and shear of a [`TriRay`].
#[derive(Clone, Copy, Debug)]
pub struct Ray4 {
    pub(super) o: [f32; 3],
    /// `kx, ky, kz`.
    pub(super) k: [usize; 3],
    /// `sx, sy, sz`.
    pub(super) s: [f32; 3],
}

impl Ray4 {
    /// Takes the permutation and shear the scalar test uses for this ray.
    #[inline]
    pub fn new(tri: &TriRay) -> Ray4 {
        let (o, k, s) = tri.parts();
        Ray4 {
            o: o.to_array(),
            k,
            s,
        }
    }

    /// The setup of `ray`: that of [`TriRay::new`], taken as [`Ray4::new`] does.
    #[inline(always)]
    pub fn from_ray(ray: &crate::math::Ray) -> Ray4 {
        Ray4::new(&TriRay::new(ray))
    }

    /// The scalar test's setup this was taken from (the same bits as the [`TriRay`] given to
    /// [`Ray4::new`]).
    #[inline(always)]
    pub fn tri(&self) -> TriRay {
        TriRay::from_parts(Vec3::from(self.o), self.k, self.s)
    }
}

/// What an `N`-lane triangle test found ([`Lanes`] for one block, `Lanes8` for a pair). Lane
/// `i` is bit `i` of the masks; the arrays hold meaningful values in `hit` lanes only (the
/// vector versions skip the rest of the work, and its stores, once no lane can hit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneHits<const N: usize> {
    /// Lanes the ray hits within `(0, t_max)` (never a `fallback` lane).
    pub hit: u32,
    /// Lanes left to the scalar test: an edge function exactly zero, no triangle (NaN), or a
    /// hit no farther than its f32 error bound.
    pub fallback: u32,
    /// Hit distances.
    pub t: [f32; N],
    /// Barycentrics `b0, b1, b2`.
    pub b: [[f32; N]; 3],
    /// The unnormalised distance `t * det` and the determinant, to re-check a hit against a
    /// smaller `t_max` ([`LaneHits::accepts`]).
    pub t_scaled: [f32; N],
    /// Determinant (sum of the edge functions).
    pub det: [f32; N],
}

/// What the four-lane test found.
pub type Lanes = LaneHits<4>;

impl<const N: usize> Default for LaneHits<N> {
    fn default() -> Self {
        LaneHits {
            hit: 0,
            fallback: 0,
            t: [0.0; N],
            b: [[0.0; N]; 3],
            t_scaled: [0.0; N],
            det: [0.0; N],
        }
    }
}

impl<const N: usize> LaneHits<N> {
    /// Whether hit lane `lane` (found with a larger `t_max`) is also a hit within `(0, t_max)`:
    /// the two conditions of the scalar test that depend on `t_max`, evaluated as it does. With
    /// it, testing lanes in order while lowering `t_max` gives exactly the scalar loop's result.
    #[inline(always)]
    pub fn accepts(&self, lane: usize, t_max: f32) -> bool {
        let (ts, det) = (self.t_scaled[lane], self.det[lane]);
        let beyond = if det < 0.0 {
            ts < t_max * det
        } else {
            ts > t_max * det
        };
        !beyond && self.t[lane] < t_max
    }
}

/// `max` as glam's `max_element` and SSE's `maxps` compute it.
#[inline(always)]
fn mx(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

/// The portable four-lane test: the same bits as [`test4_sse`] and, lane by lane, as
/// [`TriRay::intersect`] for lanes not flagged `fallback`.
#[inline]
pub fn test4_scalar(blk: &Tri4, r: &Ray4, t_max: f32) -> Lanes {
    let [kx, ky, kz] = r.k;
    let [sx, sy, sz] = r.s;
    let mut out = Lanes::default();
    for l in 0..4 {
        let p = |c: usize, k: usize| blk.v[3 * c + k][l] - r.o[k];
        let (mut ax, mut ay, mut az) = (p(0, kx), p(0, ky), p(0, kz));
        let (mut bx, mut by, mut bz) = (p(1, kx), p(1, ky), p(1, kz));
        let (mut cx, mut cy, mut cz) = (p(2, kx), p(2, ky), p(2, kz));
        ax += sx * az;
        ay += sy * az;
        bx += sx * bz;
        by += sy * bz;
        cx += sx * cz;
        cy += sy * cz;
        let e0 = bx * cy - by * cx;
        let e1 = cx * ay - cy * ax;
        let e2 = ax * by - ay * bx;
        if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 || blk.v[0][l].is_nan() {
            out.fallback |= 1 << l;
        }
        let mixed = (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0);
        let det = e0 + e1 + e2;
        let det_ok = det != 0.0 && det.abs() < f32::INFINITY;
        let max_z_len = mx(az.abs(), mx(bz.abs(), cz.abs()));
        az *= sz;
        bz *= sz;
        cz *= sz;
        let t_scaled = e0 * az + e1 * bz + e2 * cz;
        let tmd = t_max * det;
        let neg_bad = det < 0.0 && (t_scaled >= 0.0 || t_scaled < tmd);
        let pos_bad = det > 0.0 && (t_scaled <= 0.0 || t_scaled > tmd);
        let inv_det = 1.0 / det;
        let t = t_scaled * inv_det;
        let max_zt = mx(az.abs(), mx(bz.abs(), cz.abs()));
        let delta_z = gamma(3) * max_zt;
        let max_xt = mx(ax.abs(), mx(bx.abs(), cx.abs()));
        let max_yt = mx(ay.abs(), mx(by.abs(), cy.abs()));
        let delta_x = gamma(5) * (max_xt + max_z_len);
        let delta_y = gamma(5) * (max_yt + max_z_len);
        let delta_e = 2.0 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
        let max_e = mx(e0.abs(), mx(e1.abs(), e2.abs()));
        let delta_t =
            3.0 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * inv_det.abs();
        // `t <= delta_t` (false for NaN) rejects, as in the scalar test.
        let within_error = t <= delta_t;
        let pass = !mixed && det_ok && !neg_bad && !pos_bad && t < t_max;
        if pass && out.fallback & (1 << l) == 0 {
            // A distance within its error bound is the scalar test's to judge (in f64).
            if within_error {
                out.fallback |= 1 << l;
            } else {
                out.hit |= 1 << l;
            }
        }
        out.t[l] = t;
        out.b[0][l] = e0 * inv_det;
        out.b[1][l] = e1 * inv_det;
        out.b[2][l] = e2 * inv_det;
        out.t_scaled[l] = t_scaled;
        out.det[l] = det;
    }
    out
}

/// The SSE four-lane test; same contract and bits as [`test4_scalar`].
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub fn test4_sse(blk: &Tri4, r: &Ray4, t_max: f32) -> Lanes {
    use core::arch::x86_64::*;
    let [kx, ky, kz] = r.k;
    let mut out = Lanes::default();
    // SAFETY: SSE and SSE2 are in the x86_64 baseline (statically enabled on every x86_64
    // target), so the intrinsics are available. Every load reads a row `blk.v[i]` (`i < 9`,
    // bounds-checked), a `[f32; 4]` of four initialised f32s borrowed for the call; `loadu`
    // needs no alignment. Every store writes a `[f32; 4]` field of the local `out`, exclusively
    // borrowed here.
    unsafe {
        let zero = _mm_setzero_ps();
        let inf = _mm_set1_ps(f32::INFINITY);
        let sign = _mm_set1_ps(-0.0);
        let abs = |x: __m128| _mm_andnot_ps(sign, x);
        let mx = |a: __m128, b: __m128| _mm_max_ps(a, b);
        let row = |i: usize| _mm_loadu_ps(blk.v[i].as_ptr());
        let o = |k: usize| _mm_set1_ps(r.o[k]);
        let (okx, oky, okz) = (o(kx), o(ky), o(kz));
        let (sx, sy, sz) = (
            _mm_set1_ps(r.s[0]),
            _mm_set1_ps(r.s[1]),
            _mm_set1_ps(r.s[2]),
        );
        let p0x = row(0);
        let corner = |c: usize| {
            let x = _mm_sub_ps(row(3 * c + kx), okx);
            let y = _mm_sub_ps(row(3 * c + ky), oky);
            let z = _mm_sub_ps(row(3 * c + kz), okz);
            (
                _mm_add_ps(x, _mm_mul_ps(sx, z)),
                _mm_add_ps(y, _mm_mul_ps(sy, z)),
                z,
            )
        };
        let (ax, ay, az) = corner(0);
        let (bx, by, bz) = corner(1);
        let (cx, cy, cz) = corner(2);
        let e0 = _mm_sub_ps(_mm_mul_ps(bx, cy), _mm_mul_ps(by, cx));
        let e1 = _mm_sub_ps(_mm_mul_ps(cx, ay), _mm_mul_ps(cy, ax));
        let e2 = _mm_sub_ps(_mm_mul_ps(ax, by), _mm_mul_ps(ay, bx));
        let fallback = _mm_or_ps(
            _mm_or_ps(_mm_cmpeq_ps(e0, zero), _mm_cmpeq_ps(e1, zero)),
            _mm_or_ps(_mm_cmpeq_ps(e2, zero), _mm_cmpunord_ps(p0x, p0x)),
        );
        let any_neg = _mm_or_ps(
            _mm_or_ps(_mm_cmplt_ps(e0, zero), _mm_cmplt_ps(e1, zero)),
            _mm_cmplt_ps(e2, zero),
        );
        let any_pos = _mm_or_ps(
            _mm_or_ps(_mm_cmpgt_ps(e0, zero), _mm_cmpgt_ps(e1, zero)),
            _mm_cmpgt_ps(e2, zero),
        );
        let mixed = _mm_and_ps(any_neg, any_pos);
        out.fallback = _mm_movemask_ps(fallback) as u32;
        // Most blocks stop here: every lane is missed by the edge test or left to the scalar one.
        let undecided = _mm_or_ps(mixed, fallback);
        if _mm_movemask_ps(undecided) == 0b1111 {
            return out;
        }
        let det = _mm_add_ps(_mm_add_ps(e0, e1), e2);
        let det_ok = _mm_and_ps(_mm_cmpneq_ps(det, zero), _mm_cmplt_ps(abs(det), inf));
        let (szx, szy, szz) = (_mm_mul_ps(az, sz), _mm_mul_ps(bz, sz), _mm_mul_ps(cz, sz));
        let t_scaled = _mm_add_ps(
            _mm_add_ps(_mm_mul_ps(e0, szx), _mm_mul_ps(e1, szy)),
            _mm_mul_ps(e2, szz),
        );
        let tmax = _mm_set1_ps(t_max);
        let tmd = _mm_mul_ps(tmax, det);
        let neg_bad = _mm_and_ps(
            _mm_cmplt_ps(det, zero),
            _mm_or_ps(_mm_cmpge_ps(t_scaled, zero), _mm_cmplt_ps(t_scaled, tmd)),
        );
        let pos_bad = _mm_and_ps(
            _mm_cmpgt_ps(det, zero),
            _mm_or_ps(_mm_cmple_ps(t_scaled, zero), _mm_cmpgt_ps(t_scaled, tmd)),
        );
        let inv_det = _mm_div_ps(_mm_set1_ps(1.0), det);
        let t = _mm_mul_ps(t_scaled, inv_det);
        let pass = _mm_andnot_ps(
            _mm_or_ps(undecided, _mm_or_ps(neg_bad, pos_bad)),
            _mm_and_ps(det_ok, _mm_cmplt_ps(t, tmax)),
        );
        // Blocks whose lanes all lie outside (0, t_max) stop here.
        if _mm_movemask_ps(pass) == 0 {
            return out;
        }
        // The conservative lower bound on t, as the scalar test computes it.
        let max_z_len = mx(abs(az), mx(abs(bz), abs(cz)));
        let max_zt = mx(abs(szx), mx(abs(szy), abs(szz)));
        let delta_z = _mm_mul_ps(_mm_set1_ps(gamma(3)), max_zt);
        let max_xt = mx(abs(ax), mx(abs(bx), abs(cx)));
        let max_yt = mx(abs(ay), mx(abs(by), abs(cy)));
        let g5 = _mm_set1_ps(gamma(5));
        let delta_x = _mm_mul_ps(g5, _mm_add_ps(max_xt, max_z_len));
        let delta_y = _mm_mul_ps(g5, _mm_add_ps(max_yt, max_z_len));
        let delta_e = _mm_mul_ps(
            _mm_set1_ps(2.0),
            _mm_add_ps(
                _mm_add_ps(
                    _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(gamma(2)), max_xt), max_yt),
                    _mm_mul_ps(delta_y, max_xt),
                ),
                _mm_mul_ps(delta_x, max_yt),
            ),
        );
        let max_e = mx(abs(e0), mx(abs(e1), abs(e2)));
        let sum = _mm_add_ps(
            _mm_add_ps(
                _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(gamma(3)), max_e), max_zt),
                _mm_mul_ps(delta_e, max_zt),
            ),
            _mm_mul_ps(delta_z, max_e),
        );
        let delta_t = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(3.0), sum), abs(inv_det));
        let within_error = _mm_cmple_ps(t, delta_t);
        out.hit = _mm_movemask_ps(_mm_andnot_ps(within_error, pass)) as u32;
        // A distance within its error bound is the scalar test's to judge (in f64).
        out.fallback |= _mm_movemask_ps(_mm_and_ps(within_error, pass)) as u32;
        _mm_storeu_ps(out.t.as_mut_ptr(), t);
        _mm_storeu_ps(out.b[0].as_mut_ptr(), _mm_mul_ps(e0, inv_det));
        _mm_storeu_ps(out.b[1].as_mut_ptr(), _mm_mul_ps(e1, inv_det));
        _mm_storeu_ps(out.b[2].as_mut_ptr(), _mm_mul_ps(e2, inv_det));
        _mm_storeu_ps(out.t_scaled.as_mut_ptr(), t_scaled);
        _mm_storeu_ps(out.det.as_mut_ptr(), det);
    }
    out
}

/// The four-lane test for this target: SSE on x86_64, [`test4_scalar`] elsewhere.
#[inline(always)]
pub fn test4(blk: &Tri4, r: &Ray4, t_max: f32) -> Lanes {
    #[cfg(target_arch = "x86_64")]
    {
        test4_sse(blk, r, t_max)
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        test4_scalar(blk, r, t_max)
    }
}

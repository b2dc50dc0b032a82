//! Eight watertight ray-triangle tests at once: two [`Tri4`] blocks in one AVX2 pass (one of
//! the crate's few modules allowed `unsafe`).
//!
//! [`test8_avx2`] runs, on the 256-bit register whose low half holds block `a` and high half
//! block `b`, exactly the operations of [`super::tri_block::test4_sse`] in the same order (IEEE
//! subtraction, multiplication, addition and division, no fused multiply-add, `vmaxps` for
//! `maxps`, and each SSE comparison replaced by the AVX predicate that gives the same result for
//! every input, NaN included). So lane `i < 4` reports what `test4(a)` reports in its lane `i`,
//! and lane `4 + i` what `test4(b)` reports in its lane `i`, bit for bit; [`test8_portable`] is
//! those two four-lane tests. The AVX2 version is reachable only through an
//! `slab_simd::Avx2` token (a CPU that has AVX2).
//!
//! Why `unsafe` here: the loads read through raw pointers, and calling a `#[target_feature]`
//! function from code compiled without it is `unsafe` (the token vouches for the CPU).
#![allow(unsafe_code)]

use super::tri_block::{test4, LaneHits, Lanes, Ray4, Tri4};
use crate::math::gamma;

/// What the eight-lane test found: lanes 0-3 are block `a`'s, lanes 4-7 block `b`'s.
pub type Lanes8 = LaneHits<8>;

impl LaneHits<8> {
    /// The two four-lane results side by side.
    pub fn join(a: &Lanes, b: &Lanes) -> Lanes8 {
        let cat = |x: &[f32; 4], y: &[f32; 4]| {
            let mut o = [0.0f32; 8];
            o[..4].copy_from_slice(x);
            o[4..].copy_from_slice(y);
            o
        };
        Lanes8 {
            hit: a.hit | (b.hit << 4),
            fallback: a.fallback | (b.fallback << 4),
            t: cat(&a.t, &b.t),
            b: [
                cat(&a.b[0], &b.b[0]),
                cat(&a.b[1], &b.b[1]),
                cat(&a.b[2], &b.b[2]),
            ],
            t_scaled: cat(&a.t_scaled, &b.t_scaled),
            det: cat(&a.det, &b.det),
        }
    }

    /// Whether the two results agree where they are meaningful: the masks, and every array
    /// entry of the hit lanes (compared as bits).
    pub fn same_bits(&self, o: &Lanes8) -> bool {
        let eq = |x: &[f32; 8], y: &[f32; 8]| {
            (0..8).all(|l| self.hit & (1 << l) == 0 || x[l].to_bits() == y[l].to_bits())
        };
        self.hit == o.hit
            && self.fallback == o.fallback
            && eq(&self.t, &o.t)
            && (0..3).all(|i| eq(&self.b[i], &o.b[i]))
            && eq(&self.t_scaled, &o.t_scaled)
            && eq(&self.det, &o.det)
    }
}

/// Two four-lane tests ([`test4`]): the reference the AVX2 version equals.
#[inline(always)]
pub fn test8_portable(a: &Tri4, b: &Tri4, r: &Ray4, t_max: f32) -> Lanes8 {
    let (la, lb) = (test4(a, r, t_max), test4(b, r, t_max));
    // Keep the early exits of the four-lane test: nothing to copy when neither lane hits.
    if la.hit | lb.hit == 0 {
        return Lanes8 {
            fallback: la.fallback | (lb.fallback << 4),
            ..Lanes8::default()
        };
    }
    Lanes8::join(&la, &lb)
}

/// The AVX2 eight-lane test; same bits as [`test8_portable`] in every lane it reports as hit,
/// the same `hit` and `fallback` masks.
///
/// # Safety
/// Callable (safely) only from code compiled with AVX2; elsewhere the caller must know the CPU
/// has AVX2, as a `slab_simd::Avx2` token does.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub fn test8_avx2(a: &Tri4, b: &Tri4, r: &Ray4, t_max: f32) -> Lanes8 {
    // SAFETY: this function is compiled with AVX2 enabled.
    unsafe { test8_avx2_inline(a, b, r, t_max) }
}

/// [`test8_avx2`]'s body, always inlined, so the traversal loop compiled for AVX2
/// (`slab_simd::Avx2::run`) holds it rather than a call (the compiler declined to inline
/// the `#[target_feature]` function there: a call, and the result passed through memory).
///
/// # Safety
/// The CPU must have AVX2. (Inlined into code compiled without AVX2, the intrinsics stay calls:
/// correct, but slow; the traversal inlines it into AVX2 code.) The helpers below are local
/// macros, not closures: a closure is a function of its own, compiled without AVX2 in a build
/// for baseline x86-64, so its intrinsics stayed calls even inside the AVX2 traversal (session
/// 30: the portable `dist` build took 3.4 s for what the `native` one renders in 2.5 s).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(super) unsafe fn test8_avx2_inline(a: &Tri4, b: &Tri4, r: &Ray4, t_max: f32) -> Lanes8 {
    use core::arch::x86_64::*;
    let [kx, ky, kz] = r.k;
    let mut out = Lanes8::default();
    let zero = _mm256_setzero_ps();
    let inf = _mm256_set1_ps(f32::INFINITY);
    let sign = _mm256_set1_ps(-0.0);
    macro_rules! abs {
        ($x:expr) => {
            _mm256_andnot_ps(sign, $x)
        };
    }
    macro_rules! mx {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_max_ps($x, $y)
        };
    }
    // SAFETY: `a.v[i]` and `b.v[i]` (`i < 9`, bounds-checked) are `[f32; 4]` rows of four
    // initialised f32s borrowed for the call; `loadu2` reads four f32s at each (no alignment).
    macro_rules! row {
        ($i:expr) => {
            unsafe { _mm256_loadu2_m128(b.v[$i].as_ptr(), a.v[$i].as_ptr()) }
        };
    }
    macro_rules! o {
        ($k:expr) => {
            _mm256_set1_ps(r.o[$k])
        };
    }
    let (okx, oky, okz) = (o!(kx), o!(ky), o!(kz));
    let (sx, sy, sz) = (
        _mm256_set1_ps(r.s[0]),
        _mm256_set1_ps(r.s[1]),
        _mm256_set1_ps(r.s[2]),
    );
    let p0x = row!(0);
    macro_rules! corner {
        ($c:expr) => {{
            let c: usize = $c;
            let x = _mm256_sub_ps(row!(3 * c + kx), okx);
            let y = _mm256_sub_ps(row!(3 * c + ky), oky);
            let z = _mm256_sub_ps(row!(3 * c + kz), okz);
            (
                _mm256_add_ps(x, _mm256_mul_ps(sx, z)),
                _mm256_add_ps(y, _mm256_mul_ps(sy, z)),
                z,
            )
        }};
    }
    let (ax, ay, az) = corner!(0);
    let (bx, by, bz) = corner!(1);
    let (cx, cy, cz) = corner!(2);
    let e0 = _mm256_sub_ps(_mm256_mul_ps(bx, cy), _mm256_mul_ps(by, cx));
    let e1 = _mm256_sub_ps(_mm256_mul_ps(cx, ay), _mm256_mul_ps(cy, ax));
    let e2 = _mm256_sub_ps(_mm256_mul_ps(ax, by), _mm256_mul_ps(ay, bx));
    // The SSE comparisons: `cmpeqps` is EQ_OQ, `cmpltps` LT (ordered), `cmpunordps` UNORD_Q,
    // `cmpneqps` NEQ_UQ (true when unordered), `cmpleps` LE, `cmpgtps`/`cmpgeps` (swapped
    // `cmpltps`/`cmpleps`) GT/GE; quiet and signalling predicates give the same mask.
    macro_rules! eq {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_cmp_ps::<_CMP_EQ_OQ>($x, $y)
        };
    }
    macro_rules! lt {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_cmp_ps::<_CMP_LT_OQ>($x, $y)
        };
    }
    macro_rules! gt {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_cmp_ps::<_CMP_GT_OQ>($x, $y)
        };
    }
    macro_rules! le {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_cmp_ps::<_CMP_LE_OQ>($x, $y)
        };
    }
    macro_rules! ge {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_cmp_ps::<_CMP_GE_OQ>($x, $y)
        };
    }
    macro_rules! or {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_or_ps($x, $y)
        };
    }
    macro_rules! and {
        ($x:expr, $y:expr $(,)?) => {
            _mm256_and_ps($x, $y)
        };
    }
    let fallback = or!(
        or!(eq!(e0, zero), eq!(e1, zero)),
        or!(eq!(e2, zero), _mm256_cmp_ps::<_CMP_UNORD_Q>(p0x, p0x)),
    );
    let any_neg = or!(or!(lt!(e0, zero), lt!(e1, zero)), lt!(e2, zero));
    let any_pos = or!(or!(gt!(e0, zero), gt!(e1, zero)), gt!(e2, zero));
    let mixed = and!(any_neg, any_pos);
    out.fallback = _mm256_movemask_ps(fallback) as u32;
    let undecided = or!(mixed, fallback);
    if _mm256_movemask_ps(undecided) == 0xff {
        return out;
    }
    let det = _mm256_add_ps(_mm256_add_ps(e0, e1), e2);
    let det_ok = and!(_mm256_cmp_ps::<_CMP_NEQ_UQ>(det, zero), lt!(abs!(det), inf));
    let (szx, szy, szz) = (
        _mm256_mul_ps(az, sz),
        _mm256_mul_ps(bz, sz),
        _mm256_mul_ps(cz, sz),
    );
    let t_scaled = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(e0, szx), _mm256_mul_ps(e1, szy)),
        _mm256_mul_ps(e2, szz),
    );
    let tmax = _mm256_set1_ps(t_max);
    let tmd = _mm256_mul_ps(tmax, det);
    let neg_bad = and!(lt!(det, zero), or!(ge!(t_scaled, zero), lt!(t_scaled, tmd)));
    let pos_bad = and!(gt!(det, zero), or!(le!(t_scaled, zero), gt!(t_scaled, tmd)));
    let inv_det = _mm256_div_ps(_mm256_set1_ps(1.0), det);
    let t = _mm256_mul_ps(t_scaled, inv_det);
    let pass = _mm256_andnot_ps(
        or!(undecided, or!(neg_bad, pos_bad)),
        and!(det_ok, lt!(t, tmax)),
    );
    if _mm256_movemask_ps(pass) == 0 {
        return out;
    }
    let max_z_len = mx!(abs!(az), mx!(abs!(bz), abs!(cz)));
    let max_zt = mx!(abs!(szx), mx!(abs!(szy), abs!(szz)));
    let delta_z = _mm256_mul_ps(_mm256_set1_ps(gamma(3)), max_zt);
    let max_xt = mx!(abs!(ax), mx!(abs!(bx), abs!(cx)));
    let max_yt = mx!(abs!(ay), mx!(abs!(by), abs!(cy)));
    let g5 = _mm256_set1_ps(gamma(5));
    let delta_x = _mm256_mul_ps(g5, _mm256_add_ps(max_xt, max_z_len));
    let delta_y = _mm256_mul_ps(g5, _mm256_add_ps(max_yt, max_z_len));
    let delta_e = _mm256_mul_ps(
        _mm256_set1_ps(2.0),
        _mm256_add_ps(
            _mm256_add_ps(
                _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(gamma(2)), max_xt), max_yt),
                _mm256_mul_ps(delta_y, max_xt),
            ),
            _mm256_mul_ps(delta_x, max_yt),
        ),
    );
    let max_e = mx!(abs!(e0), mx!(abs!(e1), abs!(e2)));
    let sum = _mm256_add_ps(
        _mm256_add_ps(
            _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(gamma(3)), max_e), max_zt),
            _mm256_mul_ps(delta_e, max_zt),
        ),
        _mm256_mul_ps(delta_z, max_e),
    );
    let delta_t = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(3.0), sum), abs!(inv_det));
    let within_error = le!(t, delta_t);
    out.hit = _mm256_movemask_ps(_mm256_andnot_ps(within_error, pass)) as u32;
    // A distance within its error bound is the scalar test's to judge (in f64).
    out.fallback |= _mm256_movemask_ps(and!(within_error, pass)) as u32;
    // SAFETY: each store writes the eight f32s of an `[f32; 8]` field of the local `out`,
    // exclusively borrowed here (`storeu` needs no alignment).
    unsafe {
        _mm256_storeu_ps(out.t.as_mut_ptr(), t);
        _mm256_storeu_ps(out.b[0].as_mut_ptr(), _mm256_mul_ps(e0, inv_det));
        _mm256_storeu_ps(out.b[1].as_mut_ptr(), _mm256_mul_ps(e1, inv_det));
        _mm256_storeu_ps(out.b[2].as_mut_ptr(), _mm256_mul_ps(e2, inv_det));
        _mm256_storeu_ps(out.t_scaled.as_mut_ptr(), t_scaled);
        _mm256_storeu_ps(out.det.as_mut_ptr(), det);
    }
    out
}

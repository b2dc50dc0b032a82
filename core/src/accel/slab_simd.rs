//! Eight ray-box slab tests at once, for the 8-wide BVH: one of the crate's few modules allowed
//! `unsafe`.
//!
//! Three versions compute the same bits, with the operations and order of [`super::slab`] (IEEE
//! subtraction and multiplication, no fused multiply-add; the distances reduced with integer
//! `max`/`min` on their bits):
//! - [`hit8_avx2`]: one 256-bit register per bound, on CPUs that have AVX2, detected at run time
//!   ([`Avx2::detect`]) since the binary targets the x86-64 baseline;
//! - [`hit8_sse`]: two 128-bit halves, the portable x86_64 version (SSE2 is in the baseline);
//! - [`hit8_scalar`]: a loop, for other targets and as the tests' reference.
//!
//! Callers pick one through the [`Hit8`] trait. The AVX2 version is only reachable through an
//! [`Avx2`] token, which exists only on a CPU that has AVX2; [`Avx2::run`] runs a whole
//! traversal compiled with AVX2 enabled, so the box test inlines into its loop.
//!
//! Why `unsafe` here: calling a `#[target_feature]` function from code compiled without that
//! feature is `unsafe` (the caller vouches for the CPU), and so are the CPUID/XGETBV intrinsics
//! and SSE intrinsics outside a `#[target_feature]` function. Each block says why it is sound.
#![allow(unsafe_code)]

use super::slab::{hit_scalar, RayPre, MAX_X, MIN_X};
use super::tri_block::{test4, Lanes, Ray4, Tri4};
use super::tri_block_pair::{test8_portable, Lanes8};

/// Eight boxes in SoA layout: `b[MIN_X + axis][lane]` and `b[MAX_X + axis][lane]` (the row
/// indices of [`super::slab`], which a [`RayPre`]'s planes refer to). An unused lane holds the
/// empty box (min `+inf`, max `-inf`), which no ray hits.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct Boxes8 {
    /// `[min_x, min_y, min_z, max_x, max_y, max_z]`, eight lanes each.
    pub b: [[f32; 8]; 6],
}

impl Boxes8 {
    /// Eight empty boxes.
    pub const EMPTY: Boxes8 = Boxes8 {
        b: [
            [f32::INFINITY; 8],
            [f32::INFINITY; 8],
            [f32::INFINITY; 8],
            [f32::NEG_INFINITY; 8],
            [f32::NEG_INFINITY; 8],
            [f32::NEG_INFINITY; 8],
        ],
    };
}

// The rows start where the bounds' indices say.
const _: () = assert!(MIN_X == 0 && MAX_X == 3);

/// The reference slab test: bit `i` of the mask is set when the ray meets box `i` within
/// `[0, t_max]`; `t_near[i]` is where it enters (meaningful for set bits only).
#[inline]
pub fn hit8_scalar(boxes: &Boxes8, ray: &RayPre, t_max: f32) -> (u32, [f32; 8]) {
    hit_scalar(&boxes.b, ray, t_max)
}

/// The slab test on two SSE halves; same contract and bits as [`hit8_scalar`]. SSE2 has no
/// `pmaxsd`/`pminsd` (SSE4.1): a compare and a blend stand in for them.
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn hit8_sse(boxes: &Boxes8, ray: &RayPre, t_max: f32) -> (u32, [f32; 8]) {
    use core::arch::x86_64::*;
    // SAFETY (both helpers): SSE2 is in the x86_64 baseline; register operations only.
    let max = |a: __m128i, b: __m128i| unsafe {
        let gt = _mm_cmpgt_epi32(a, b);
        _mm_or_si128(_mm_and_si128(gt, a), _mm_andnot_si128(gt, b))
    };
    let min = |a: __m128i, b: __m128i| unsafe {
        let gt = _mm_cmpgt_epi32(a, b);
        _mm_or_si128(_mm_and_si128(gt, b), _mm_andnot_si128(gt, a))
    };
    let mut t_near = [0.0f32; 8];
    let mut mask = 0;
    for half in 0..2 {
        let at = 4 * half;
        // SAFETY: SSE and SSE2 are in the x86_64 baseline (statically enabled on every x86_64
        // target). The loads read four f32s at `at..at + 4` (at most 8) of a row of `boxes.b`,
        // an `[f32; 8]` borrowed for the call (`loadu` needs no alignment); the store writes
        // four f32s at `at..at + 4` of the local `[f32; 8]` `t_near`.
        mask |= unsafe {
            let mut tn = _mm_setzero_si128();
            let mut tf = _mm_castps_si128(_mm_set1_ps(t_max));
            for a in 0..3 {
                let near = _mm_loadu_ps(boxes.b[ray.near[a]].as_ptr().add(at));
                let far = _mm_loadu_ps(boxes.b[ray.far[a]].as_ptr().add(at));
                let t0 = _mm_mul_ps(
                    _mm_sub_ps(near, _mm_set1_ps(ray.o[a])),
                    _mm_set1_ps(ray.inv[a]),
                );
                let t1 = _mm_mul_ps(
                    _mm_sub_ps(far, _mm_set1_ps(ray.o_far[a])),
                    _mm_set1_ps(ray.inv_far[a]),
                );
                tn = max(_mm_castps_si128(t0), tn);
                tf = min(_mm_castps_si128(t1), tf);
            }
            _mm_storeu_si128(t_near.as_mut_ptr().add(at).cast(), tn);
            // Hit where not `tn > tf`.
            ((_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(tn, tf))) ^ 0xf) as u32) << at
        };
    }
    (mask, t_near)
}

/// The AVX2 slab test; same contract and bits as [`hit8_scalar`]. The reductions are balanced
/// (two levels of one-cycle integer operations), so the mask is ready one subtraction, one
/// multiplication and about four cycles after the node's boxes arrive.
///
/// # Safety
/// Callable (safely) only from code compiled with AVX2; elsewhere the caller must know the CPU
/// has AVX2, as an [`Avx2`] token does ([`Hit8`] for [`Avx2`], [`Avx2::run`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub fn hit8_avx2(boxes: &Boxes8, ray: &RayPre, t_max: f32) -> (u32, [f32; 8]) {
    use core::arch::x86_64::*;
    let mut t_near = [0.0f32; 8];
    let mut t0 = [_mm256_setzero_si256(); 3];
    let mut t1 = [_mm256_setzero_si256(); 3];
    for a in 0..3 {
        // SAFETY: each load reads the eight f32s of a row of `boxes.b`, an `[f32; 8]` borrowed
        // for the call (`loadu` needs no alignment).
        let (near, far) = unsafe {
            (
                _mm256_loadu_ps(boxes.b[ray.near[a]].as_ptr()),
                _mm256_loadu_ps(boxes.b[ray.far[a]].as_ptr()),
            )
        };
        let o = _mm256_set1_ps(ray.o[a]);
        let o_far = _mm256_set1_ps(ray.o_far[a]);
        t0[a] = _mm256_castps_si256(_mm256_mul_ps(
            _mm256_sub_ps(near, o),
            _mm256_set1_ps(ray.inv[a]),
        ));
        t1[a] = _mm256_castps_si256(_mm256_mul_ps(
            _mm256_sub_ps(far, o_far),
            _mm256_set1_ps(ray.inv_far[a]),
        ));
    }
    // Integer max/min are exact and associative: the balanced order gives the scalar loop's bits.
    let tn = _mm256_max_epi32(
        _mm256_max_epi32(t0[0], t0[1]),
        _mm256_max_epi32(t0[2], _mm256_setzero_si256()),
    );
    let tf = _mm256_min_epi32(
        _mm256_min_epi32(t1[0], t1[1]),
        _mm256_min_epi32(t1[2], _mm256_castps_si256(_mm256_set1_ps(t_max))),
    );
    // SAFETY: the store writes the eight f32s of the local `t_near`, exclusively borrowed here.
    unsafe { _mm256_storeu_si256(t_near.as_mut_ptr().cast(), tn) };
    // Hit where not `tn > tf`.
    let miss = _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(tn, tf))) as u32;
    (miss ^ 0xff, t_near)
}

/// Asks the CPU to bring the first `bytes` bytes of `slice[i]` into the cache: a hint, with no
/// effect on results (nothing on targets without a prefetch instruction here). No bounds check:
/// prefetching an address outside the slice is harmless.
#[inline(always)]
pub(crate) fn prefetch_in<T>(slice: &[T], i: usize, bytes: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // Address arithmetic only: the pointer is never dereferenced.
        let p = slice.as_ptr().wrapping_add(i).cast::<i8>();
        let mut at = 0;
        while at < bytes {
            // SAFETY: `prefetcht0` (SSE, in the x86_64 baseline) never faults, whatever the
            // address, and has no architectural effect.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(at)) };
            at += 64;
        }
        // A type aligned to lines whose size is a whole number of lines is covered by the steps.
        let covered = core::mem::align_of::<T>().is_multiple_of(64) && bytes.is_multiple_of(64);
        if bytes > 0 && !covered {
            // SAFETY: as above (the last byte's line, which the steps may not reach).
            unsafe { _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(bytes - 1)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let _ = (slice, i, bytes);
    }
}

/// An eight-box slab test and the triangle tests of the leaves, chosen by type so a traversal
/// loop compiles with one set of them inlined.
pub trait Hit8: Copy {
    /// Mask of the boxes the ray meets within `[0, t_max]`, and their entry distances.
    fn hit8(self, boxes: &Boxes8, ray: &RayPre, t_max: f32) -> (u32, [f32; 8]);

    /// The four-lane triangle test ([`test4`]; the same everywhere, compiled with the caller's
    /// features).
    #[inline(always)]
    fn tri4(self, blk: &Tri4, ray: &Ray4, t_max: f32) -> Lanes {
        test4(blk, ray, t_max)
    }

    /// Two blocks' triangle tests at once, `a` in lanes 0-3 and `b` in lanes 4-7
    /// ([`super::tri_block_pair`]).
    fn tri8(self, a: &Tri4, b: &Tri4, ray: &Ray4, t_max: f32) -> Lanes8;
}

/// The portable test: two SSE halves on x86_64, the scalar loop elsewhere.
#[derive(Clone, Copy, Debug)]
pub struct Portable;

impl Hit8 for Portable {
    #[inline(always)]
    fn hit8(self, boxes: &Boxes8, ray: &RayPre, t_max: f32) -> (u32, [f32; 8]) {
        #[cfg(target_arch = "x86_64")]
        {
            hit8_sse(boxes, ray, t_max)
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            hit8_scalar(boxes, ray, t_max)
        }
    }

    #[inline(always)]
    fn tri8(self, a: &Tri4, b: &Tri4, ray: &Ray4, t_max: f32) -> Lanes8 {
        test8_portable(a, b, ray, t_max)
    }
}

/// Proof that this CPU runs AVX2 (and POPCNT) code: only [`Avx2::detect`] makes one, and only
/// when it does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Avx2 {
    _private: (),
}

impl Avx2 {
    /// Asks the CPU (CPUID, XGETBV): AVX2 and POPCNT present, the AVX registers enabled by the
    /// OS.
    pub fn detect() -> Option<Avx2> {
        #[cfg(target_arch = "x86_64")]
        {
            use core::arch::x86_64::{__cpuid, __cpuid_count, _xgetbv};
            // CPUID is available on every x86_64 CPU.
            let max_leaf = __cpuid(0).eax;
            let l1 = __cpuid(1);
            let osxsave = l1.ecx & (1 << 27) != 0;
            let avx = l1.ecx & (1 << 28) != 0;
            // POPCNT (every AVX2 CPU has it): the traversal counts hit children with it.
            let popcnt = l1.ecx & (1 << 23) != 0;
            if max_leaf < 7 || !osxsave || !avx || !popcnt {
                return None;
            }
            // SAFETY: CPUID.1:ECX.OSXSAVE (checked above) says the OS has enabled XSAVE, which
            // makes XGETBV executable; XCR0 (register 0) always exists then.
            let xcr0 = unsafe { _xgetbv(0) };
            // The OS saves the XMM (bit 1) and YMM (bit 2) state across context switches.
            if xcr0 & 0b110 != 0b110 {
                return None;
            }
            let avx2 = __cpuid_count(7, 0).ebx & (1 << 5) != 0;
            avx2.then_some(Avx2 { _private: () })
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            None
        }
    }

    /// Runs `work` inside a function compiled with AVX2 enabled, with this token as its box
    /// test, so the test (and everything `work` inlines: its [`WithHit8::call`] must be
    /// `#[inline(always)]`) is compiled for AVX2. Floating-point results are those of the
    /// portable build: AVX2 brings no fused multiply-add, and the compiler does not contract or
    /// reorder IEEE operations.
    #[inline(always)]
    pub fn run<W: WithHit8>(self, work: W) -> W::Output {
        #[cfg(all(
            target_arch = "x86_64",
            not(all(target_feature = "avx2", target_feature = "popcnt"))
        ))]
        {
            // SAFETY: `self` exists only when `detect` found AVX2 and POPCNT usable on this CPU.
            unsafe { run_avx2(self, work) }
        }
        // A build for CPUs that have AVX2 (`-C target-cpu=native` on one) compiles every
        // function with it: the traversal then inlines into its caller like any other code.
        #[cfg(any(
            not(target_arch = "x86_64"),
            all(target_feature = "avx2", target_feature = "popcnt")
        ))]
        {
            work.call(self)
        }
    }
}

/// Work generic over the box test, such as a traversal loop, so it can be compiled once per test
/// ([`Avx2::run`]). A trait rather than a closure: the compiler may decline to inline a large
/// closure into the AVX2 function, which would leave the box test an out-of-line call.
pub trait WithHit8 {
    /// What the work returns.
    type Output;
    /// Does the work with box test `test` (implementations: `#[inline(always)]`).
    fn call<H: Hit8>(self, test: H) -> Self::Output;
}

/// `work.call(token)`, compiled with AVX2 and POPCNT (`call` is inlined into this function,
/// monomorphised per use).
#[cfg(all(
    target_arch = "x86_64",
    not(all(target_feature = "avx2", target_feature = "popcnt"))
))]
#[target_feature(enable = "avx2,popcnt")]
#[inline]
fn run_avx2<W: WithHit8>(token: Avx2, work: W) -> W::Output {
    work.call(token)
}

impl Hit8 for Avx2 {
    #[inline(always)]
    fn hit8(self, boxes: &Boxes8, ray: &RayPre, t_max: f32) -> (u32, [f32; 8]) {
        #[cfg(target_arch = "x86_64")]
        {
            // SAFETY: `self` exists only when `detect` found AVX2 usable on this CPU.
            unsafe { hit8_avx2(boxes, ray, t_max) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            hit8_scalar(boxes, ray, t_max)
        }
    }

    #[inline(always)]
    fn tri8(self, a: &Tri4, b: &Tri4, ray: &Ray4, t_max: f32) -> Lanes8 {
        #[cfg(target_arch = "x86_64")]
        {
            // SAFETY: `self` exists only when `detect` found AVX2 usable on this CPU (the body
            // is fast where it inlines into AVX2 code, as in [`Avx2::run`]).
            unsafe { super::tri_block_pair::test8_avx2_inline(a, b, ray, t_max) }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            test8_portable(a, b, ray, t_max)
        }
    }
}

//! A hint that data will soon be read: the cache line holding a value is requested now, so
//! that a later load finds it near the core.
//!
//! Used where a batch of paths knows what each will read next (an escaped ray's environment
//! texels, a hit's mesh corners) and can ask for all of them before any is needed: the misses
//! then overlap instead of waiting one after another. A prefetch changes no value; off x86_64
//! it does nothing.
//!
//! The `unsafe` block is the intrinsic call: `prefetcht0` is part of SSE, which every x86_64
//! CPU has, and the address comes from a reference, so it points at live memory (a prefetch
//! never faults in any case).
#![allow(unsafe_code)]

/// Asks for the cache line holding `value` to be brought into every level of the cache.
#[inline(always)]
pub fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: SSE is part of the x86_64 baseline; the pointer comes from a reference.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((value as *const T).cast::<i8>()) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

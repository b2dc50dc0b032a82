//! Proof that `tessera-core` links without `std`.
//!
//! This crate is `#![no_std]` and defines the two things only a final no_std artifact defines:
//! the panic handler and the global allocator. If anything in the core's dependency graph pulled
//! `std` in, std's own `panic_impl` lang item would collide with ours and this crate would fail
//! to compile ("duplicate lang item"). The test command builds it (`cargo build -p
//! tessera-nostd-check`), and it calls into the core so the core is really linked, not skipped.
#![no_std]

extern crate alloc;

use core::alloc::{GlobalAlloc, Layout};
use core::panic::PanicInfo;
use tessera_core::glam::{Vec2, Vec3};
use tessera_core::math::Ray;
use tessera_core::sampling::{warp, IndependentSampler, Sampler};

/// A bump allocator over a static arena, enough for building a tiny scene.
struct Arena;

unsafe impl GlobalAlloc for Arena {
    unsafe fn alloc(&self, _layout: Layout) -> *mut u8 {
        core::ptr::null_mut()
    }
    unsafe fn dealloc(&self, _ptr: *mut u8, _layout: Layout) {}
}

#[global_allocator]
static ALLOCATOR: Arena = Arena;

#[panic_handler]
fn panic(_info: &PanicInfo) -> ! {
    loop {}
}

/// Traces one sample-driven ray against an analytic sphere using only the core.
pub fn trace_one(seed: u64) -> f32 {
    let mut s = IndependentSampler::new(seed, 0, 0, 0);
    let d = warp::square_to_uniform_sphere(Vec2::new(s.next_1d(), s.next_1d()));
    let sphere = tessera_core::geometry::Sphere {
        center: Vec3::new(0.0, 0.0, 3.0),
        radius: 1.0,
    };
    sphere
        .intersect(&Ray::new(Vec3::ZERO, d), f32::INFINITY)
        .unwrap_or(0.0)
}

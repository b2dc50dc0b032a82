//! SplitMix64: a small deterministic generator for test data (meshes, rays, triangle cases).

use tessera_core::glam::Vec3;

/// SplitMix64 state; the same seed always gives the same sequence.
pub struct SplitMix(pub u64);

impl SplitMix {
    /// The next 64 random bits.
    pub fn u(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` with 24 bits.
    pub fn f(&mut self) -> f32 {
        (self.u() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in the cube of side `s` centred at the origin.
    pub fn v(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5) * s
    }

    /// An index in `0..n` from the 64 bits (modulo).
    pub fn below(&mut self, n: usize) -> usize {
        (self.u() % n as u64) as usize
    }

    /// An index in `0..n` from [`SplitMix::f`] (scaled), as the BVH tests draw theirs.
    pub fn below_scaled(&mut self, n: usize) -> usize {
        ((self.f() * n as f32) as usize).min(n - 1)
    }
}

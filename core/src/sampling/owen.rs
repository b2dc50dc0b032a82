//! Hash-based Owen scrambling (nested uniform scrambling in base 2) of 32-bit binary fractions
//! and of 64-bit sequence indices.
//!
//! Owen scrambling flips each bit of a number by a random function of the bits *above* it. Such
//! a map is a bijection that sends every aligned block of `2^k` consecutive values (an elementary
//! interval, for a fraction) to another aligned block of the same size, so it keeps the
//! stratification of a `(t, m, s)`-net while randomizing it. Computing one independent random
//! bit per prefix is expensive; the Laine-Karras construction gets the same nested structure in a
//! few instructions by reversing the bits (so "the bits above" become "the bits below") and
//! applying operations whose output bit `k` depends only on input bits `0..=k`: adding a
//! constant, multiplying by an odd number and `x ^= x * even`. The constants are those of Nathan
//! Vegdahl's improved LK hash ("Building a Better LK Hash", psychopath.io, 2021), which is known
//! to decorrelate well; the seed must be well mixed beforehand (callers pass hashes).

/// The Laine-Karras-style permutation of a bit-reversed value: output bit `k` is input bit `k`
/// flipped by a function of input bits `0..k` and the seed.
#[inline]
pub(crate) fn reversed_lk(mut n: u32, seed: u32) -> u32 {
    n ^= n.wrapping_mul(0x3d20_adea);
    n = n.wrapping_add(seed);
    n = n.wrapping_mul((seed >> 16) | 1);
    n ^= n.wrapping_mul(0x0552_6c56);
    n ^= n.wrapping_mul(0x53a2_2864);
    n
}

/// Owen-scrambles a 32-bit binary fraction (`v / 2^32`): bit `31 - k` is flipped by a
/// pseudo-random function of `seed` and the `k` bits above it.
#[inline]
pub fn owen_scramble_u32(v: u32, seed: u32) -> u32 {
    reversed_lk(v.reverse_bits(), seed).reverse_bits()
}

/// SplitMix64's finalizer: a bijective 64-bit mixer.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The pixel multiplier of [`sample_seed`].
pub(crate) const SAMPLE_SEED_MUL: u64 = 0x2545_f491_4f6c_dd1d;

/// The seed of the sample part's scramble in [`scramble_index`].
#[inline]
pub fn sample_seed(seed: u64, pixel: u64) -> u32 {
    mix64(seed ^ pixel.wrapping_mul(SAMPLE_SEED_MUL)) as u32
}

/// A nested random permutation of indices `i < 2^(32 + k)` split as `(pixel << k) | sample`
/// (`k <= 32`): bit `j` is flipped by a pseudo-random function of `seed` and the bits above `j`,
/// so every aligned block of `2^j` indices goes to an aligned block of `2^j` indices. The pixel
/// part is Owen-scrambled as a 32-bit word seeded by `seed`; the sample part's scramble is
/// seeded by a fresh hash of `seed` and the whole (unscrambled) pixel part, so each pixel picks
/// its block of samples independently of its neighbours.
#[inline]
pub fn scramble_index(i: u64, k: u32, seed: u64) -> u64 {
    let k = k.min(32);
    let pixel = i >> k;
    let hi = owen_scramble_u32(pixel as u32, seed as u32) as u64;
    if k == 0 {
        return hi;
    }
    let sample = (i as u32) << (32 - k);
    let lo_seed = sample_seed(seed, pixel);
    (hi << k) | (owen_scramble_u32(sample, lo_seed) >> (32 - k)) as u64
}

//! The independent sampler: one PCG32 stream per pixel, one window of it per sample.
//!
//! Scene parameters (`<sampler type="independent">`): `sample_count` (integer, default 4; read by
//! the driver). The random stream of a sample is a pure function of
//! `(seed, pixel x, pixel y, sample index)`: the seed and pixel are hashed into a PCG32 state and
//! stream selector, and the generator is advanced by `sample index * 2^32`, so each sample owns a
//! window of 2^32 draws. Nothing depends on tiles, threads or time, and one sample can be
//! replayed alone.
use super::Sampler;
use rand_core::Rng;
use rand_pcg::Pcg32;

/// Draws a sample may use before it would run into the next sample's window.
pub(crate) const SAMPLE_WINDOW: u64 = 1 << 32;

/// SplitMix64's finalizer: a bijective 64-bit mixer.
#[inline]
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The 64-bit key of a pixel under a seed (distinct pixels give unrelated keys).
#[inline]
pub(crate) fn pixel_key(seed: u64, x: u32, y: u32) -> u64 {
    mix64(seed ^ mix64((((x as u64) << 32) | y as u64) ^ 0x9e37_79b9_7f4a_7c15))
}

/// Independent uniform samples from a PCG32 stream keyed by seed, pixel and sample index.
#[derive(Clone, Debug)]
pub struct IndependentSampler {
    rng: Pcg32,
}

impl IndependentSampler {
    /// The stream of sample `index` of pixel `(x, y)` under `seed`.
    pub fn new(seed: u64, x: u32, y: u32, index: u64) -> Self {
        let (start, stream) = pixel_stream(seed, x, y);
        let state = skip_windows(start, (stream << 1) | 1, index);
        IndependentSampler {
            rng: Pcg32::from_state(state, stream),
        }
    }

    /// The streams of samples `indices` of pixel `(x, y)` under `seed`, in order: the same
    /// samplers [`IndependentSampler::new`] makes, found with one hash of the pixel and one jump
    /// over the first index for the whole run, then one multiply-add per sample (each window starts
    /// one window after the one before). A render loop that makes a pixel's samplers one after
    /// another spends far less on them this way.
    pub fn pixel_run(
        seed: u64,
        x: u32,
        y: u32,
        indices: core::ops::Range<u64>,
    ) -> impl Iterator<Item = IndependentSampler> {
        let (start, stream) = pixel_stream(seed, x, y);
        let inc = (stream << 1) | 1;
        let mut state = skip_windows(start, inc, indices.start);
        let (a, h) = WINDOW_JUMP;
        let step = inc.wrapping_mul(h);
        indices.map(move |_| {
            let sampler = IndependentSampler {
                rng: Pcg32::from_state(state, stream),
            };
            state = a.wrapping_mul(state).wrapping_add(step);
            sampler
        })
    }
}

/// The state sample 0 of pixel `(x, y)` under `seed` starts from, and the pixel's stream.
#[inline]
fn pixel_stream(seed: u64, x: u32, y: u32) -> (u64, u64) {
    let key = pixel_key(seed, x, y);
    let start = Pcg32::new(key, mix64(key ^ 0xda94_2042_e4dd_58b5));
    (start.state(), start.stream())
}

/// PCG32's multiplier (the LCG under `rand_pcg::Pcg32`).
const PCG_MULT: u64 = 6_364_136_223_846_793_005;

/// The LCG's jump over one window ([`SAMPLE_WINDOW`] = 2^32 steps), as `(a, h)`: from state `s` with increment `c`
/// the state 2^32 steps on is `a s + c h` (mod 2^64). The increment enters the jump linearly, so
/// `h` is the jump's additive part for increment 1.
const WINDOW_JUMP: (u64, u64) = {
    let (mut a, mut h) = (PCG_MULT, 1u64);
    let mut k = 0;
    while k < SAMPLE_WINDOW.trailing_zeros() {
        // Two jumps of 2^k make one of 2^(k+1): (a, h) then (a, h) is (a^2, (a + 1) h).
        h = a.wrapping_add(1).wrapping_mul(h);
        a = a.wrapping_mul(a);
        k += 1;
    }
    (a, h)
};

/// The state `n` windows (`n * 2^32` steps) after `state`, for increment `inc`: the same state
/// `Pcg32::advance(n * 2^32)` reaches (exact arithmetic mod 2^64), by square-and-multiply over
/// the bits of `n` alone instead of the bits of `n * 2^32`.
#[inline]
fn skip_windows(state: u64, inc: u64, mut n: u64) -> u64 {
    let (mut acc_a, mut acc_h) = (1u64, 0u64);
    let (mut a, mut h) = WINDOW_JUMP;
    while n > 0 {
        if n & 1 != 0 {
            acc_a = acc_a.wrapping_mul(a);
            acc_h = acc_h.wrapping_mul(a).wrapping_add(h);
        }
        h = a.wrapping_add(1).wrapping_mul(h);
        a = a.wrapping_mul(a);
        n >>= 1;
    }
    acc_a
        .wrapping_mul(state)
        .wrapping_add(inc.wrapping_mul(acc_h))
}

impl Sampler for IndependentSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        // 24 high bits: exactly representable, strictly below 1.
        (self.rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pixel's run of samplers draws what samplers made one by one draw, for runs starting
    /// at zero, inside and near the end of the index range. Control: a run started one index
    /// late differs.
    #[test]
    fn a_pixel_run_is_the_samplers_made_one_by_one() {
        let draws =
            |mut s: IndependentSampler| -> [f32; 4] { core::array::from_fn(|_| s.next_1d()) };
        for (seed, x, y) in [(0u64, 0u32, 0u32), (7, 123, 45), (u64::MAX, u32::MAX, 9)] {
            for start in [0u64, 1, 5, 1000, (1 << 33) + 7, u64::MAX - 40] {
                let run: alloc::vec::Vec<[f32; 4]> =
                    IndependentSampler::pixel_run(seed, x, y, start..start + 40)
                        .map(draws)
                        .collect();
                for (k, got) in run.iter().enumerate() {
                    let want = draws(IndependentSampler::new(seed, x, y, start + k as u64));
                    assert_eq!(
                        *got,
                        want,
                        "seed {seed} pixel ({x}, {y}) index {}",
                        start + k as u64
                    );
                }
                let late: alloc::vec::Vec<[f32; 4]> =
                    IndependentSampler::pixel_run(seed, x, y, start + 1..start + 41)
                        .map(draws)
                        .collect();
                assert_ne!(run, late, "control");
            }
        }
    }

    /// The window jump lands on the state `rand_pcg`'s own `advance` reaches, for small, large
    /// and wrapping sample indices and several streams; the control, one step short, does not.
    #[test]
    fn skipping_windows_is_pcg_advance() {
        for key in [0u64, 1, 0x1234_5678_9abc_def0, u64::MAX] {
            let start = Pcg32::new(key, mix64(key ^ 0xda94_2042_e4dd_58b5));
            let inc = (start.stream() << 1) | 1;
            for n in [
                0u64,
                1,
                2,
                3,
                7,
                1000,
                65_537,
                (1 << 31) + 5,
                (1 << 32) + 3,
                u64::MAX,
            ] {
                let mut by_advance = start.clone();
                by_advance.advance(n.wrapping_mul(SAMPLE_WINDOW));
                assert_eq!(
                    skip_windows(start.state(), inc, n),
                    by_advance.state(),
                    "n {n}"
                );
                let mut short = start.clone();
                short.advance(n.wrapping_mul(SAMPLE_WINDOW).wrapping_sub(1));
                assert_ne!(skip_windows(start.state(), inc, n), short.state(), "n {n}");
            }
        }
    }
}

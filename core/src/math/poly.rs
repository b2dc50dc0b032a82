//! Polynomial evaluation for the fitted approximations (`arc.rs`, `turns.rs`).

/// `c[0] x^(n-1) + c[1] x^(n-2) + ... + c[n-1]` by Horner's rule, highest coefficient first:
/// `p = p * x + c` for each later coefficient, in `f32` and without fused multiply-add, so the
/// same bits on every target.
#[inline(always)]
pub(crate) fn horner<const N: usize>(x: f32, c: [f32; N]) -> f32 {
    let mut p = c[0];
    for &k in &c[1..] {
        p = p * x + k;
    }
    p
}

//! Multiple importance sampling weights.

/// Veach's power heuristic (exponent 2) for the strategy with density `a` against `b`.
#[inline]
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    if a.is_infinite() {
        return 1.0;
    }
    let (a2, b2) = (a * a, b * b);
    if !(a2 + b2 > 0.0) {
        return 0.0;
    }
    if b2.is_infinite() {
        return 0.0;
    }
    a2 / (a2 + b2)
}

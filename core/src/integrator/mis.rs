//! Multiple importance sampling weights.

/// Veach's power heuristic (exponent 2) for the strategy with density `a` against `b`.
#[inline]
pub(crate) fn power_heuristic(a: f32, b: f32) -> f32 {
    if a.is_infinite() {
        return 1.0;
    }
    let (a2, b2) = (a * a, b * b);
    if !(a2 + b2 > 0.0) || b2.is_infinite() {
        return 0.0;
    }
    a2 / (a2 + b2)
}

/// Veach's balance heuristic for the strategy with density `a` against `b`.
#[inline]
pub(crate) fn balance_heuristic(a: f32, b: f32) -> f32 {
    if a.is_infinite() {
        return 1.0;
    }
    if !(a + b > 0.0) || b.is_infinite() {
        return 0.0;
    }
    a / (a + b)
}

/// Which MIS heuristic combines two strategies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Heuristic {
    /// `a^2 / (a^2 + b^2)`: Mitsuba 3's choice and the default.
    #[default]
    Power,
    /// `a / (a + b)`: the Wakame assignment's choice.
    Balance,
}

impl Heuristic {
    /// Weight of the strategy with (sample-count scaled) density `a` against `b`.
    #[inline]
    pub fn weight(self, a: f32, b: f32) -> f32 {
        match self {
            Heuristic::Power => power_heuristic(a, b),
            Heuristic::Balance => balance_heuristic(a, b),
        }
    }
}

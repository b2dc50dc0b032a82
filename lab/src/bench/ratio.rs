//! How long one curve takes to reach a relMSE compared with a peer's curve (`tessera bench
//! --ratio-to CURVE`): the ratio of the two times to target, or the bound on it that the curves
//! allow when one of them reached the target at its first wave or never reached it.
use super::{time_to_target, Row, TimeToTarget};

/// `ours / peer` of the times to reach a relMSE.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ratio {
    /// Both curves reached the target between two waves.
    Exact(f64),
    /// At most this: this curve reached the target at its first wave, or the peer never did.
    AtMost(f64),
    /// At least this: this curve never reached the target, or the peer did at its first wave.
    AtLeast(f64),
    /// The curves bound it on neither side (neither reached the target, or both at their
    /// first wave).
    Unknown,
}

/// The interval `[lo, hi]` the curve's time to `target` lies in: one point when reached between
/// waves, `[0, first wave]` when the first wave reached it, `[last wave, inf]` when no wave did.
fn bounds(curve: &[Row], target: f64) -> (f64, f64) {
    match time_to_target(curve, target) {
        TimeToTarget::Interpolated(s) => (s, s),
        TimeToTarget::AtMost(s) => (0.0, s),
        TimeToTarget::NotReached { .. } => {
            let last = curve.iter().map(|r| r.seconds).fold(0.0, f64::max);
            (last, f64::INFINITY)
        }
    }
}

/// The ratio of `ours`'s time to reach `target` to `peer`'s.
pub fn ratio(ours: &[Row], peer: &[Row], target: f64) -> Ratio {
    let (o_lo, o_hi) = bounds(ours, target);
    let (p_lo, p_hi) = bounds(peer, target);
    // `ours / peer` lies in [o_lo / p_hi, o_hi / p_lo].
    let lo = o_lo / p_hi;
    let hi = o_hi / p_lo;
    let known = |x: f64| x.is_finite() && x > 0.0;
    if o_lo == o_hi && p_lo == p_hi && known(lo) {
        Ratio::Exact(lo)
    } else if known(hi) {
        Ratio::AtMost(hi)
    } else if known(lo) {
        Ratio::AtLeast(lo)
    } else {
        Ratio::Unknown
    }
}

impl std::fmt::Display for Ratio {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Ratio::Exact(r) => write!(f, "{r:.2}x"),
            Ratio::AtMost(r) => write!(f, "<= {r:.2}x"),
            Ratio::AtLeast(r) => write!(f, ">= {r:.2}x"),
            Ratio::Unknown => write!(f, "unknown"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_row;
    use super::*;

    fn curve(points: &[(f64, f64)]) -> Vec<Row> {
        points.iter().map(|&(s, e)| test_row(s, e)).collect()
    }

    #[test]
    fn exact_when_both_reach_the_target_between_waves() {
        // relMSE 1/t for ours, 2/t for the peer: 0.01 at 100 s and 200 s.
        let ours = curve(&[(50.0, 0.02), (200.0, 0.005)]);
        let peer = curve(&[(100.0, 0.02), (400.0, 0.005)]);
        match ratio(&ours, &peer, 0.01) {
            Ratio::Exact(r) => assert!((r - 0.5).abs() < 1e-12, "{r}"),
            r => panic!("{r:?}"),
        }
    }

    /// Same kind of answer, values equal up to the rounding of the log-log interpolation.
    fn assert_near(got: Ratio, want: Ratio) {
        let ok = match (got, want) {
            (Ratio::Exact(a), Ratio::Exact(b))
            | (Ratio::AtMost(a), Ratio::AtMost(b))
            | (Ratio::AtLeast(a), Ratio::AtLeast(b)) => (a - b).abs() < 1e-9,
            (a, b) => a == b,
        };
        assert!(ok, "got {got:?}, want {want:?}");
    }

    #[test]
    fn bounds_when_a_curve_stops_short_or_starts_below() {
        let ours = curve(&[(1.0, 0.02), (4.0, 0.005)]); // 0.01 at 2 s
        let short = curve(&[(1.0, 0.05), (8.0, 0.02)]); // never reaches 0.01
        let early = curve(&[(0.5, 0.001), (1.0, 0.0005)]); // reaches 0.01 by its first wave
                                                           // The peer needs more than its last 8 s: ours / peer < 2 / 8.
        assert_near(ratio(&ours, &short, 0.01), Ratio::AtMost(0.25));
        // We never reach it (more than 8 s), the peer does at 2 s: at least 4x.
        assert_near(ratio(&short, &ours, 0.01), Ratio::AtLeast(4.0));
        // Reached at our first wave (at most 0.5 s) against the peer's 2 s.
        assert_near(ratio(&early, &ours, 0.01), Ratio::AtMost(0.25));
        assert_near(ratio(&ours, &early, 0.01), Ratio::AtLeast(4.0));
        // Neither bound exists.
        assert_near(ratio(&short, &short, 0.01), Ratio::Unknown);
        assert_near(ratio(&early, &early, 0.01), Ratio::Unknown);
        assert_eq!(Ratio::AtMost(0.25).to_string(), "<= 0.25x");
        assert_eq!(Ratio::Exact(0.7712).to_string(), "0.77x");
    }
}

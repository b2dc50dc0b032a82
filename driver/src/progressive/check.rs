//! The error check of `--target-error`: at every check point (each doubling of the samples per
//! pixel) the render's relative MSE is estimated from the two halves of its samples
//! ([`halves_rel_mse`]), the state at the previous check point being the first half.
//!
//! Check points are fixed sample counts, never times: uniform passes end at every power of two
//! spp, adaptive ones at every doubling of the mean. So the render stops at the same count, with
//! the same bits, on any machine and thread count.
use tessera_core::error_estimate::{halves_rel_mse, MIN_CHECK_SPP};
use tessera_core::film::PixelAccum;

/// The relMSE floor of the estimate (the bench's measure).
const FLOOR: f64 = 0.01;

/// The accumulators at a check point, which the next check takes as its first half (a
/// checkpoint file keeps them, so a resumed render checks where an uninterrupted one would).
#[derive(Clone, Debug, PartialEq)]
pub struct CheckState {
    /// Samples per pixel at the check point (the mean, for adaptive renders).
    pub spp: u64,
    /// The estimate made there (`None`: none was, e.g. below [`MIN_CHECK_SPP`]).
    pub estimate: Option<f64>,
    /// Every pixel's accumulators there.
    pub pixels: Vec<PixelAccum>,
}

/// State between check points.
#[derive(Clone, Debug)]
pub(crate) struct ErrorCheck {
    target: f64,
    /// The previous check point.
    previous: Option<CheckState>,
    /// The latest estimate.
    pub last: Option<f64>,
}

impl ErrorCheck {
    /// A check for the relative MSE `target`, continuing from `previous` (a resumed render's
    /// last check point, or `None`).
    pub fn new(target: f64, previous: Option<CheckState>) -> Self {
        ErrorCheck {
            target,
            last: previous.as_ref().and_then(|p| p.estimate),
            previous,
        }
    }

    /// Called at a check point, `pixels` holding `spp` samples per pixel (the mean): estimates
    /// the error when the previous check point held half as many and `spp` is at least
    /// [`MIN_CHECK_SPP`], then keeps this state. Returns whether the estimate reached the target.
    pub fn at(&mut self, spp: u64, pixels: &[PixelAccum]) -> bool {
        let mut estimate = None;
        if let Some(before) = &self.previous {
            if before.spp.saturating_mul(2) == spp && spp >= MIN_CHECK_SPP {
                estimate = halves_rel_mse(&before.pixels, pixels, FLOOR);
                self.last = estimate;
            }
        }
        self.previous = Some(CheckState {
            spp,
            estimate,
            pixels: pixels.to_vec(),
        });
        self.reached(spp)
    }

    /// Whether the check point at `spp` (the latest one) reached the target: a resumed render
    /// that was saved after its last check has nothing left to do.
    pub fn reached(&self, spp: u64) -> bool {
        self.previous
            .as_ref()
            .is_some_and(|p| p.spp == spp && p.estimate.is_some_and(|e| e <= self.target))
    }

    /// The latest check point, for a checkpoint file.
    pub fn state(&self) -> Option<&CheckState> {
        self.previous.as_ref()
    }
}

/// The end of a uniform pass from `low` spp that would end at `end`, cut at the next power of two
/// above `low`, so that every power of two is a pass end.
pub(crate) fn clamp_to_check_point(low: u64, end: u64) -> u64 {
    end.min(
        low.saturating_add(1)
            .checked_next_power_of_two()
            .unwrap_or(u64::MAX),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use tessera_core::Color;

    #[test]
    fn pass_ends_stop_at_powers_of_two() {
        assert_eq!(clamp_to_check_point(0, 1), 1);
        assert_eq!(clamp_to_check_point(1, 3), 2);
        assert_eq!(clamp_to_check_point(2, 9), 4);
        assert_eq!(clamp_to_check_point(4, 6), 6);
        assert_eq!(clamp_to_check_point(6, 20), 8);
        assert_eq!(clamp_to_check_point(8, 16), 16);
        assert_eq!(clamp_to_check_point(u64::MAX - 1, u64::MAX), u64::MAX);
    }

    /// Estimates only from 16 spp on and only with the state at half the count: a constant
    /// image reaches any target then, not before.
    #[test]
    fn checks_need_the_half_and_enough_samples() {
        let image = |n: usize| {
            let mut p = PixelAccum::default();
            for _ in 0..n {
                p.add(Color::splat(0.5));
            }
            vec![p; 4]
        };
        let mut c = ErrorCheck::new(1e-9, None);
        assert!(!c.at(4, &image(4)));
        assert!(!c.at(8, &image(8)));
        assert_eq!(c.last, None);
        // 32 after 8: not a doubling, no estimate.
        assert!(!c.at(32, &image(32)));
        assert_eq!(c.last, None);
        assert!(c.at(64, &image(64)));
        assert_eq!(c.last, Some(0.0));
    }
}

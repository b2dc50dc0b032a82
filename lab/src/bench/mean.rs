//! One curve from several: the same integrator and sampler measured with different seeds,
//! averaged wave by wave (`tessera bench --seeds N`, `scripts/mitsuba_bench.py --seeds N`).
//!
//! The error of one low-sample-count image depends much on its seed (veach_mis, 128x128, zsobol,
//! 4 spp: over 8 seeds, one seed's relMSE has a standard deviation of 17% of the mean), and with
//! it the time a curve needs to reach a target. The mean over seeds estimates the expected error, which is what "time to equal
//! error" compares. Seconds, relMSE, MSE and MAE are averaged; RMSE is the root of the mean MSE.
use super::{Errors, Row};

/// The wave-by-wave mean of `curves` (each in wave order, all of one integrator and sampler),
/// over the waves every curve reached (curves may stop at different waves when their time
/// limit is predicted differently). Rows are matched by position and must have the same
/// samples per pixel; `None` if they do not, or if there is no curve.
pub fn mean_curve(curves: &[Vec<Row>]) -> Option<Vec<Row>> {
    let first = curves.first()?;
    let waves = curves.iter().map(Vec::len).min().unwrap_or(0);
    let n = curves.len() as f64;
    let mut out = Vec::with_capacity(waves);
    for k in 0..waves {
        let head = &first[k];
        let rows: Vec<&Row> = curves.iter().map(|c| &c[k]).collect();
        if rows.iter().any(|r| r.spp != head.spp) {
            return None;
        }
        let mean = |f: &dyn Fn(&Row) -> f64| rows.iter().map(|r| f(r)).sum::<f64>() / n;
        let seconds = mean(&|r| r.seconds);
        let pixel_samples = head.samples_per_second * head.seconds;
        out.push(Row {
            seconds,
            samples_per_second: pixel_samples / seconds.max(1e-9),
            errors: Errors {
                rmse: mean(&|r| r.errors.rmse * r.errors.rmse).sqrt(),
                relmse: mean(&|r| r.errors.relmse),
                mae: mean(&|r| r.errors.mae),
            },
            ..head.clone()
        });
    }
    Some(out)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A row of curve `path (zsobol)`, 2 threads, 100 pixels.
    pub(crate) fn row(spp: u64, seconds: f64, rmse: f64, relmse: f64, mae: f64) -> Row {
        Row {
            integrator: "path".into(),
            sampler: "zsobol".into(),
            spp,
            threads: 2,
            seconds,
            samples_per_second: 100.0 * spp as f64 / seconds,
            errors: Errors { rmse, relmse, mae },
        }
    }

    /// Means of seconds, relMSE and MAE, RMSE from the mean MSE, samples per second from the
    /// mean seconds; only the waves both curves reached.
    #[test]
    fn averages_wave_by_wave_over_the_common_waves() {
        let a = vec![row(1, 1.0, 3.0, 0.4, 1.0), row(2, 2.0, 1.0, 0.2, 0.5)];
        let b = vec![
            row(1, 3.0, 4.0, 0.2, 2.0),
            row(2, 6.0, 7.0, 0.1, 1.5),
            row(4, 12.0, 1.0, 0.05, 1.0),
        ];
        let m = mean_curve(&[a, b]).unwrap();
        assert_eq!(m.len(), 2);
        assert_eq!(m[0].spp, 1);
        assert_eq!(m[1].spp, 2);
        assert!((m[0].seconds - 2.0).abs() < 1e-12);
        assert!((m[0].errors.rmse - 12.5f64.sqrt()).abs() < 1e-12);
        assert!((m[0].errors.relmse - 0.3).abs() < 1e-12);
        assert!((m[0].errors.mae - 1.5).abs() < 1e-12);
        assert!((m[0].samples_per_second - 50.0).abs() < 1e-9);
        assert!((m[1].seconds - 4.0).abs() < 1e-12);
        assert!((m[1].errors.rmse - 25.0f64.sqrt()).abs() < 1e-12);
        assert!((m[1].errors.relmse - 0.15).abs() < 1e-12);
        assert!((m[1].samples_per_second - 50.0).abs() < 1e-9);
        assert_eq!(m[1].integrator, "path");
        assert_eq!(m[1].sampler, "zsobol");
    }

    /// One curve is its own mean (up to the RMSE's square and root).
    #[test]
    fn one_curve_is_its_own_mean() {
        let a = vec![row(1, 1.5, 0.3, 0.4, 1.0), row(2, 2.5, 0.2, 0.2, 0.5)];
        let m = mean_curve(std::slice::from_ref(&a)).unwrap();
        for (x, y) in m.iter().zip(&a) {
            assert_eq!(x.seconds, y.seconds);
            assert_eq!(x.errors.relmse, y.errors.relmse);
            assert!((x.errors.rmse - y.errors.rmse).abs() < 1e-15);
        }
    }

    /// Curves whose waves do not line up, and no curve at all, have no mean.
    #[test]
    fn mismatched_or_missing_curves_have_no_mean() {
        let a = vec![row(1, 1.0, 1.0, 1.0, 1.0)];
        let b = vec![row(2, 1.0, 1.0, 1.0, 1.0)];
        assert_eq!(mean_curve(&[a, b]), None);
        assert_eq!(mean_curve(&[]), None);
    }
}

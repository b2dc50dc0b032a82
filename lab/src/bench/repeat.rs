//! One curve from repeated identical runs: the same integrator, sampler and seed rendered
//! several times (`tessera bench --repeats N`, `scripts/mitsuba_bench.py --repeats N`), each
//! wave keeping its fastest time.
//!
//! A run's images do not depend on the machine's load, but its seconds do: on the shared
//! two-core machines the benchmark runs on, another job can slow any wave, and the first waves
//! of a curve last a few milliseconds, where one such hiccup decides the time to reach an error.
//! The fastest of several runs estimates the time the work itself takes. Both renderers'
//! curves are measured the same way (Mitsuba's script times each wave's render `N` times too), so
//! their ratio compares like with like.
//!
//! The runs must agree on every image: a wave whose errors differ from the first run's is
//! reported as an error (a render that changes between identical runs is not deterministic).
use super::Row;

/// The wave-by-wave fastest of `runs` (each in wave order, all of one integrator, sampler and
/// seed), over the waves every run reached (runs may stop at different waves when their time
/// limit is predicted differently): each row keeps the least seconds of its wave and the
/// samples per second that go with them. `Err` names the first wave whose sample count or
/// errors differ between runs; `Ok(empty)` when there is no run.
pub fn fastest_curve(runs: &[Vec<Row>]) -> Result<Vec<Row>, String> {
    let Some(first) = runs.first() else {
        return Ok(Vec::new());
    };
    let waves = runs.iter().map(Vec::len).min().unwrap_or(0);
    let mut out = Vec::with_capacity(waves);
    for k in 0..waves {
        let head = &first[k];
        let mut seconds = head.seconds;
        for (i, run) in runs.iter().enumerate().skip(1) {
            let r = &run[k];
            if r.spp != head.spp || r.errors != head.errors {
                return Err(format!(
                    "{} ({}): repeat {} differs from the first at wave {} ({} spp): \
                     relMSE {:e} against {:e}",
                    head.integrator,
                    head.sampler,
                    i + 1,
                    k + 1,
                    r.spp,
                    r.errors.relmse,
                    head.errors.relmse
                ));
            }
            seconds = seconds.min(r.seconds);
        }
        let pixel_samples = head.samples_per_second * head.seconds;
        out.push(Row {
            seconds,
            samples_per_second: pixel_samples / seconds.max(1e-9),
            ..head.clone()
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row whose errors all follow from `relmse`.
    fn row(spp: u64, seconds: f64, relmse: f64) -> Row {
        super::super::mean::tests::row(spp, seconds, relmse.sqrt(), relmse, relmse / 2.0)
    }

    /// Each wave keeps its own least time (from any run), the errors of all runs (which agree),
    /// and the samples per second of that time; only the waves every run reached.
    #[test]
    fn keeps_each_waves_least_time_over_the_common_waves() {
        let a = vec![row(1, 1.0, 0.4), row(2, 3.0, 0.2), row(4, 9.0, 0.1)];
        let b = vec![row(1, 2.0, 0.4), row(2, 2.5, 0.2)];
        let c = vec![row(1, 0.5, 0.4), row(2, 4.0, 0.2), row(4, 5.0, 0.1)];
        let f = fastest_curve(&[a.clone(), b, c]).unwrap();
        assert_eq!(f.len(), 2);
        assert_eq!((f[0].spp, f[0].seconds), (1, 0.5));
        assert_eq!((f[1].spp, f[1].seconds), (2, 2.5));
        assert_eq!(f[0].errors, a[0].errors);
        assert_eq!(f[1].errors, a[1].errors);
        assert!((f[0].samples_per_second - 200.0).abs() < 1e-9);
        assert!((f[1].samples_per_second - 80.0).abs() < 1e-9);
        assert_eq!(
            (f[1].integrator.as_str(), f[1].sampler.as_str()),
            ("path", "zsobol")
        );
    }

    /// One run is its own fastest curve.
    #[test]
    fn one_run_is_its_own_fastest() {
        let a = vec![row(1, 1.5, 0.4), row(2, 2.5, 0.2)];
        assert_eq!(fastest_curve(std::slice::from_ref(&a)).unwrap(), a);
        assert_eq!(fastest_curve(&[]).unwrap(), Vec::<Row>::new());
    }

    /// Runs whose images differ (another error or sample count at some wave) are an error that
    /// names the repeat and the wave.
    #[test]
    fn runs_that_disagree_are_an_error() {
        let a = vec![row(1, 1.0, 0.4), row(2, 2.0, 0.2)];
        let b = vec![row(1, 1.0, 0.4), row(2, 2.0, 0.25)];
        let e = fastest_curve(&[a.clone(), a.clone(), b]).unwrap_err();
        assert!(
            e.contains("repeat 3") && e.contains("wave 2 (2 spp)"),
            "{e}"
        );
        let c = vec![row(2, 1.0, 0.4)];
        assert!(fastest_curve(&[a, c]).unwrap_err().contains("wave 1"));
    }
}

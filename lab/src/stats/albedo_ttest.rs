//! Student t-test of a BSDF's directional albedo: the mean of its sampled weights against a
//! reference value, as in Nori's `<test type="ttest">` with `<bsdf>` children.
//!
//! # Method
//!
//! For a fixed incident direction `wi` and surface point `uv`, `samples` triples
//! `(u1, u2.x, u2.y)` from a [`Pcg32`] are passed to `Bsdf::sample`; a failed sample counts as
//! weight 0 (as in Nori, where a failed sample returns black). The expected weight is the
//! directional albedo `∫ f(wi, wo) |cos θo| dωo` plus, for delta components, the sum of their
//! discrete probabilities times their weights — whatever the sampling strategy is, as long as
//! it is unbiased. So comparing the sample mean with an independently computed albedo checks
//! `sample`'s weights (and its delta probabilities) against the model.
//!
//! The compared quantity is either the luminance of the weight (Nori's choice, with Nori's
//! weights, see [`luminance`]) or each RGB channel separately; in the latter case the three
//! channel tests are combined by taking the smallest p-value, Šidák-adjusted for three tests
//! (`1 - (1 - p_min)^3`).
//!
//! The test itself is Student's, as [`t_test_mean_f32`](super::ttest::t_test_mean_f32) but with a
//! wider floor: the weights are computed in single precision by a chain of operations (a
//! Fresnel term, a masking term) that the reference (Mitsuba 3, also in single precision)
//! evaluates in its own order, so [`ROUNDING_ULPS`] f32 ulps of the reference join the standard
//! error. In particular a deterministic weight (zero variance: `diffuse`, whose weight is its
//! reflectance, or a smooth conductor's Fresnel reflectance) passes when the mean equals the
//! reference within f32 rounding and fails otherwise: a relative error of 1e-5 gives `t > 5`.

use glam::{DVec3, Vec2, Vec3};
use statrs::distribution::{ContinuousCDF, StudentsT};
use tessera_core::bsdf::Bsdf;

use super::rng::Pcg32;
use super::ttest::{Moments, TTest};

/// Round-off allowed between the sampled weights and the reference, in f32 ulps of the
/// reference: both sides evaluate the model's formulas in single precision, each rounding
/// several times.
pub const ROUNDING_ULPS: f64 = 16.0;

/// Student's t-test of `H0: E[x] = reference` with `ROUNDING_ULPS` f32 ulps of the reference
/// added to the standard error (in quadrature). With zero variance and a zero reference the
/// mean must be 0 within f64 round-off.
fn rounding_t_test(m: &Moments, reference: f64) -> TTest {
    let n = m.count() as f64;
    let (mean, dof) = (m.mean(), n - 1.0);
    let floor = ROUNDING_ULPS * f64::from(f32::EPSILON) * reference.abs();
    let se2 = m.variance() / n + floor * floor;
    let diff = mean - reference;
    if se2 == 0.0 || !se2.is_finite() {
        let equal = diff.abs() <= 4.0 * f64::EPSILON * mean.abs().max(reference.abs());
        return TTest {
            t: if equal {
                0.0
            } else {
                diff.signum() * f64::INFINITY
            },
            dof,
            p_value: if diff.is_nan() {
                f64::NAN
            } else {
                f64::from(u8::from(equal))
            },
        };
    }
    let t = diff / se2.sqrt();
    let p_value = if t.is_nan() {
        f64::NAN
    } else {
        let dist = StudentsT::new(0.0, 1.0, dof).expect("at least 2 samples");
        (2.0 * dist.sf(t.abs())).min(1.0)
    };
    TTest { t, dof, p_value }
}

/// Nori's luminance weights (Rec. 709 primaries), as used by its `ttest`.
pub(crate) const LUMINANCE_WEIGHTS: [f64; 3] = [0.212671, 0.715160, 0.072169];

/// Nori's luminance of a linear RGB value.
pub fn luminance(c: DVec3) -> f64 {
    LUMINANCE_WEIGHTS[0] * c.x + LUMINANCE_WEIGHTS[1] * c.y + LUMINANCE_WEIGHTS[2] * c.z
}

/// What the sample mean is compared with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlbedoReference {
    /// The luminance of the expected weight (Nori's `ttest`).
    Luminance(f64),
    /// The expected weight per channel.
    Rgb([f64; 3]),
}

/// Outcome of [`albedo_t_test`].
#[derive(Clone, Debug, PartialEq)]
pub struct AlbedoTTest {
    /// Sample means of the compared quantities (one for luminance, three for RGB).
    pub means: Vec<f64>,
    /// The references, in the same order.
    pub references: Vec<f64>,
    /// Standard errors of the means.
    pub std_errors: Vec<f64>,
    /// One t-test per compared quantity.
    pub tests: Vec<TTest>,
    /// The decisive test: the one with the smallest p-value, whose p-value is Šidák-adjusted
    /// for the number of quantities (unchanged for luminance). Reject when `p_value < alpha`.
    pub test: TTest,
    /// How many `sample` calls failed (counted as weight 0).
    pub failed_samples: usize,
}

impl AlbedoTTest {
    /// `true` if the mean agrees with the reference at level `alpha`.
    pub fn passes(&self, alpha: f64) -> bool {
        self.test.passes(alpha)
    }
}

/// Runs the t-test of the mean sampled weight of `bsdf` at `wi` (unit, local frame) and `uv`
/// against `reference`, with `samples` draws from `Pcg32::new(seed)`.
///
/// # Panics
/// With fewer than 2 samples (a test with one sample is a bug in the test).
pub fn albedo_t_test(
    bsdf: &Bsdf,
    wi: Vec3,
    uv: Vec2,
    reference: AlbedoReference,
    samples: usize,
    seed: u64,
) -> AlbedoTTest {
    assert!(samples >= 2, "albedo t-test needs at least 2 samples");
    let refs: Vec<f64> = match reference {
        AlbedoReference::Luminance(r) => vec![r],
        AlbedoReference::Rgb(r) => r.to_vec(),
    };
    let mut moments = vec![Moments::new(); refs.len()];
    let mut rng = Pcg32::new(seed);
    let mut failed_samples = 0;
    for _ in 0..samples {
        let u1 = rng.next_f32();
        let u2 = rng.next_vec2();
        let w = match bsdf.sample(wi, u1, u2, uv) {
            Some(s) => s.weight.as_dvec3(),
            None => {
                failed_samples += 1;
                DVec3::ZERO
            }
        };
        match reference {
            AlbedoReference::Luminance(_) => moments[0].push(luminance(w)),
            AlbedoReference::Rgb(_) => {
                for (m, v) in moments.iter_mut().zip(w.to_array()) {
                    m.push(v);
                }
            }
        }
    }
    let tests: Vec<TTest> = moments
        .iter()
        .zip(&refs)
        .map(|(m, &r)| rounding_t_test(m, r))
        .collect();
    // The smallest p-value decides (NaN, from a non-finite weight, counts as smallest).
    let worst = tests
        .iter()
        .copied()
        .min_by(|a, b| {
            let key = |t: &TTest| if t.p_value.is_nan() { -1.0 } else { t.p_value };
            key(a).total_cmp(&key(b))
        })
        .expect("at least one quantity");
    let k = tests.len() as f64;
    let test = TTest {
        p_value: -(k * (-worst.p_value).ln_1p()).exp_m1(),
        ..worst
    };
    AlbedoTTest {
        means: moments.iter().map(Moments::mean).collect(),
        references: refs,
        std_errors: moments.iter().map(Moments::std_error).collect(),
        tests,
        test,
        failed_samples,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tessera_core::bsdf::{Diffuse, TwoSided};
    use tessera_core::texture::Texture;

    fn diffuse(r: [f32; 3]) -> Bsdf {
        Bsdf::Diffuse(Diffuse {
            reflectance: Texture::Constant(Vec3::from(r)),
        })
    }

    const WI: Vec3 = Vec3::new(0.6, 0.0, 0.8);

    #[test]
    fn deterministic_weight_is_compared_within_f32_rounding() {
        let b = diffuse([0.7, 0.5, 0.3]);
        // The weight is the reflectance in f32: 0.7f32 = 0.699999988..., yet the decimal
        // reference passes; one part in 1e5 off fails.
        let lum = luminance(DVec3::new(0.7, 0.5, 0.3));
        let r = albedo_t_test(&b, WI, Vec2::ZERO, AlbedoReference::Luminance(lum), 1000, 1);
        assert_eq!(r.std_errors[0], 0.0);
        assert!(r.passes(0.01) && r.test.p_value > 0.5, "{r:?}");
        let r = albedo_t_test(
            &b,
            WI,
            Vec2::ZERO,
            AlbedoReference::Luminance(lum * (1.0 + 1e-5)),
            1000,
            1,
        );
        assert!(r.test.p_value < 1e-6, "{r:?}");
        let rgb = AlbedoReference::Rgb([0.7, 0.5, 0.3]);
        assert!(albedo_t_test(&b, WI, Vec2::ZERO, rgb, 100, 2).passes(0.01));
        let rgb = AlbedoReference::Rgb([0.7, 0.5, 0.301]);
        let r = albedo_t_test(&b, WI, Vec2::ZERO, rgb, 100, 2);
        assert!(!r.passes(1e-9), "{r:?}");
        assert!(
            r.tests[2].p_value < 1e-100 && r.tests[0].p_value > 0.5,
            "{r:?}"
        );
    }

    #[test]
    fn failed_samples_count_as_zero() {
        // A one-sided diffuse seen from the back: every sample fails, the albedo is 0.
        let b = diffuse([0.7, 0.5, 0.3]);
        let back = Vec3::new(0.6, 0.0, -0.8);
        let r = albedo_t_test(&b, back, Vec2::ZERO, AlbedoReference::Luminance(0.0), 50, 3);
        assert_eq!(r.failed_samples, 50);
        assert!(r.passes(0.01), "{r:?}");
        let r = albedo_t_test(&b, back, Vec2::ZERO, AlbedoReference::Luminance(0.1), 50, 3);
        assert!(!r.passes(1e-9), "{r:?}");
        // Wrapped in twosided, the back sees the model again.
        let t = Bsdf::TwoSided(TwoSided {
            front: Box::new(diffuse([0.1; 3])),
            back: Box::new(b),
        });
        let lum = luminance(DVec3::new(0.7, 0.5, 0.3));
        let r = albedo_t_test(&t, back, Vec2::ZERO, AlbedoReference::Luminance(lum), 50, 3);
        assert!(r.passes(0.01), "{r:?}");
    }
}

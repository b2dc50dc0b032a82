//! Chi-square test of a BSDF's `sample` against its own `pdf`, delta components included, and
//! the per-sample consistency checks that go with it.
//!
//! # Method
//!
//! For a fixed incident direction `wi` and surface point `uv`, `samples` triples
//! `(u1, u2.x, u2.y)` from a [`Pcg32`] are passed to `Bsdf::sample`.
//!
//! - A smooth sample (`delta == false`) is counted in one of the equal-solid-angle cells of the
//!   sphere (as in [`SphereChi2`](super::sphere_chi2::SphereChi2)); its expected count is `samples` times the
//!   integral of `Bsdf::pdf` over the cell.
//! - A delta sample is counted in a bin of its own per distinct direction (directions are told
//!   apart after rounding to 1e-3); its expected count is `samples` times the discrete
//!   probability the sample claims in `pdf`, which must be the same every time that direction
//!   comes up.
//!
//! One Pearson test over all cells and delta bins then checks the smooth shape and the split
//! between components at once. Where only one outcome is possible (a mirror, total internal
//! reflection) there is nothing to compare: the test passes when every sample took that outcome
//! and its claimed probability is 1, and fails otherwise. The smooth pdf integral plus the delta probabilities must be 1
//! (at most 1 if sampling ever failed).
//!
//! Each smooth sample must also be consistent with `eval` and `pdf` at its direction:
//! `sample.pdf == pdf(wo)` and `sample.weight * sample.pdf == eval(wo)` (relative 1e-3 plus a
//! small absolute slack). More than `samples / 10^4` inconsistent samples (rounding near
//! grazing angles is allowed that many) fail the test with the first offender in the message.
//! A non-finite or negative weight, a non-unit direction, or a non-positive pdf fails at once.

use std::collections::HashMap;
use std::f64::consts::TAU;
use tessera_core::math::Norm;

use glam::{Vec2, Vec3};
use tessera_core::bsdf::{Bsdf, BsdfSample};

use super::chi2::{chi2_test, Chi2Result, DEFAULT_MIN_EXPECTED};
use super::histogram::cell_index;
use super::quadrature::grid_probabilities;
use super::rng::Pcg32;

/// Chi-square test configuration for BSDF sampling.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BsdfChi2 {
    /// Cells in `cos theta` over `[-1, 1]`.
    pub theta_bins: usize,
    /// Cells in `phi` over `[0, 2 pi)`.
    pub phi_bins: usize,
    /// Number of `sample` calls.
    pub samples: usize,
}

impl Default for BsdfChi2 {
    /// 20 x 40 cells (the lobes of glossy models are narrower than a warp's), 1e6 samples.
    fn default() -> Self {
        BsdfChi2 {
            theta_bins: 20,
            phi_bins: 40,
            samples: 1_000_000,
        }
    }
}

/// A delta direction's bin.
struct DeltaBin {
    wo: Vec3,
    prob: f32,
    count: f64,
}

fn rel_close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()) + abs
}

impl BsdfChi2 {
    /// Runs the test for `bsdf` at `wi` (unit, local frame) and `uv`; deterministic for a
    /// given `seed`.
    ///
    /// # Panics
    /// If any bin count or `samples` is zero.
    pub fn run(&self, bsdf: &Bsdf, wi: Vec3, uv: Vec2, seed: u64) -> Chi2Result {
        self.run_with(
            |u1, u2| bsdf.sample(wi, u1, u2, uv),
            |wo| bsdf.pdf(wi, wo, uv),
            |wo| bsdf.eval(wi, wo, uv),
            seed,
        )
    }

    /// [`BsdfChi2::run`] for any sampler with its claimed `pdf` and `eval` (at a fixed `wi`).
    pub(crate) fn run_with(
        &self,
        mut sample: impl FnMut(f32, Vec2) -> Option<BsdfSample>,
        pdf_of: impl Fn(Vec3) -> f32,
        eval_of: impl Fn(Vec3) -> tessera_core::Color,
        seed: u64,
    ) -> Chi2Result {
        let (nt, np) = (self.theta_bins, self.phi_bins);
        assert!(
            nt > 0 && np > 0 && self.samples > 0,
            "BsdfChi2: empty configuration"
        );
        let mut rng = Pcg32::new(seed);
        let mut observed = vec![0.0f64; nt * np];
        let mut deltas: HashMap<[i32; 3], DeltaBin> = HashMap::new();
        let mut failures = 0usize;
        let mut inconsistent = 0usize;
        let mut first_bad: Option<String> = None;
        for k in 0..self.samples {
            let u1 = rng.next_f32();
            let u2 = rng.next_vec2();
            let Some(s) = sample(u1, u2) else {
                failures += 1;
                continue;
            };
            let len = s.wo.norm();
            if !s.wo.is_finite() || (len - 1.0).abs() > 1e-3 {
                return Chi2Result::failure(format!(
                    "sample {k}: direction {} is not a unit vector",
                    s.wo
                ));
            }
            if !(s.pdf > 0.0 && s.pdf.is_finite()) {
                return Chi2Result::failure(format!("sample {k}: pdf {} for {}", s.pdf, s.wo));
            }
            if !s.weight.is_finite() || s.weight.min_element() < 0.0 || !(s.eta > 0.0) {
                return Chi2Result::failure(format!(
                    "sample {k}: weight {} / eta {} for {}",
                    s.weight, s.eta, s.wo
                ));
            }
            if s.delta {
                let r = (s.wo * 1e3).round();
                let key = [r.x as i32, r.y as i32, r.z as i32];
                let bin = deltas.entry(key).or_insert(DeltaBin {
                    wo: s.wo,
                    prob: s.pdf,
                    count: 0.0,
                });
                if !rel_close(bin.prob, s.pdf, 1e-4, 1e-7) {
                    return Chi2Result::failure(format!(
                        "delta direction {}: probability {} and later {}",
                        bin.wo, bin.prob, s.pdf
                    ));
                }
                bin.count += 1.0;
                continue;
            }
            let pdf = pdf_of(s.wo);
            let f = eval_of(s.wo);
            let fw = s.weight * s.pdf;
            let ok = rel_close(s.pdf, pdf, 1e-3, 1e-6)
                && (0..3).all(|c| rel_close(fw[c], f[c], 1e-3, 1e-6));
            if !ok {
                inconsistent += 1;
                if first_bad.is_none() {
                    first_bad = Some(format!(
                        "wo = {}: sample pdf {} vs pdf() {}, weight*pdf {} vs eval() {}",
                        s.wo, s.pdf, pdf, fw, f
                    ));
                }
            }
            let (x, y, z) = (f64::from(s.wo.x), f64::from(s.wo.y), f64::from(s.wo.z));
            let mut phi = y.atan2(x);
            if phi < 0.0 {
                phi += TAU;
            }
            observed[cell_index(0.5 * (z + 1.0), nt) * np + cell_index(phi / TAU, np)] += 1.0;
        }

        let mut bad_pdf: Option<(Vec3, f64)> = None;
        let mut density = |z: f64, phi: f64| {
            let r = (1.0 - z * z).max(0.0).sqrt();
            let w = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
            let v = f64::from(pdf_of(w));
            if !(v.is_finite() && v >= 0.0) && bad_pdf.is_none() {
                bad_pdf = Some((w, v));
            }
            v
        };
        let probs = grid_probabilities(&mut density, (-1.0, 1.0, nt), (0.0, TAU, np), self.samples);
        if let Some((w, v)) = bad_pdf {
            return Chi2Result::failure(format!("pdf({w}) = {v} is negative or not finite"));
        }
        let n = self.samples as f64;
        let mut expected: Vec<f64> = probs.iter().map(|p| p * n).collect();
        let mut total: f64 = probs.iter().sum();
        let mut bins: Vec<_> = deltas.into_values().collect();
        bins.sort_by(|a, b| a.wo.to_array().partial_cmp(&b.wo.to_array()).unwrap());
        for b in &bins {
            observed.push(b.count);
            expected.push(f64::from(b.prob) * n);
            total += f64::from(b.prob);
        }
        // A single possible outcome (a mirror; total internal reflection) leaves nothing for a
        // chi-square to compare: the test is then that every sample took it and that its
        // claimed probability is 1 (the integral check below).
        let outcomes = expected.iter().filter(|&&e| e > 0.0).count();
        let single = outcomes == 1
            && failures == 0
            && observed
                .iter()
                .zip(&expected)
                .all(|(&o, &e)| (e > 0.0) == (o > 0.0) && (e == 0.0 || o == n));
        let mut result = if single {
            Chi2Result {
                statistic: 0.0,
                dof: 0,
                p_value: 1.0,
                pooled_cells: 0,
                pdf_integral: None,
                message: None,
            }
        } else {
            chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED)
        };
        result.check_pdf_integral(total, failures);
        if inconsistent * 10_000 > self.samples {
            result.fail_with(format!(
                "{inconsistent} samples disagree with eval/pdf, e.g. {}",
                first_bad.unwrap_or_default()
            ));
        }
        result
    }
}

/// Mean and standard error of the sampled weight `f cos / pdf` over `samples` draws: an
/// estimate of the directional albedo at `wi` (per channel).
pub fn sampled_albedo(bsdf: &Bsdf, wi: Vec3, uv: Vec2, samples: usize, seed: u64) -> (Vec3, Vec3) {
    let mut rng = Pcg32::new(seed);
    let (mut s, mut s2) = (glam::DVec3::ZERO, glam::DVec3::ZERO);
    for _ in 0..samples {
        let u1 = rng.next_f32();
        let u2 = rng.next_vec2();
        if let Some(b) = bsdf.sample(wi, u1, u2, uv) {
            let w = b.weight.as_dvec3();
            s += w;
            s2 += w * w;
        }
    }
    let n = samples as f64;
    let mean = s / n;
    let var = (s2 / n - mean * mean).max(glam::DVec3::ZERO) * (n / (n - 1.0).max(1.0));
    (mean.as_vec3(), (var / n).powf(0.5).as_vec3())
}

#[cfg(test)]
mod tests {
    use super::*;
    use tessera_core::bsdf::Diffuse;
    use tessera_core::texture::Texture;

    fn diffuse(r: f32) -> Bsdf {
        Bsdf::Diffuse(Diffuse {
            reflectance: Texture::constant(r),
        })
    }

    #[test]
    fn diffuse_passes_and_albedo_is_reflectance() {
        let wi = Vec3::new(0.3, 0.2, 0.9).unit();
        let r = BsdfChi2::default().run(&diffuse(0.7), wi, Vec2::ZERO, 1);
        assert!(r.passes(0.01), "{r}");
        let (m, _) = sampled_albedo(&diffuse(0.7), wi, Vec2::ZERO, 1000, 2);
        assert!((m - Vec3::splat(0.7)).abs().max_element() < 1e-6);
    }

    #[test]
    fn a_single_outcome_passes_only_with_probability_one() {
        let mirror = |prob: f32| {
            move |wi: Vec3| tessera_core::bsdf::BsdfSample {
                wo: Vec3::new(-wi.x, -wi.y, wi.z),
                weight: Vec3::ONE,
                pdf: prob,
                delta: true,
                eta: 1.0,
            }
        };
        let wi = Vec3::new(0.3, 0.2, 0.9).unit();
        let t = BsdfChi2::default();
        let ok = t.run_with(|_, _| Some(mirror(1.0)(wi)), |_| 0.0, |_| Vec3::ZERO, 1);
        assert!(ok.passes(0.01), "{ok}");
        let bad = t.run_with(|_, _| Some(mirror(0.9)(wi)), |_| 0.0, |_| Vec3::ZERO, 1);
        assert!(!bad.passes(0.01), "{bad}");
    }

    #[test]
    fn back_side_samples_nothing() {
        let r = BsdfChi2::default().run(&diffuse(0.7), -Vec3::Z, Vec2::ZERO, 1);
        // Every sample fails, so there are no cells: the test cannot pass.
        assert!(!r.passes(0.01), "{r}");
    }
}

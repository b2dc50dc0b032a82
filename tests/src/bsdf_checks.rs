//! Checks that several material test files run the same way: a list of chi-square cases judged
//! together at one Šidák level, a sampler judged against another material's density (the
//! controls), finite and self-consistent values at extreme parameters, the sampled albedo
//! against a quadrature of `eval`, reciprocity, and what the path loop is told about a smooth
//! material.
//! Each file keeps its own cases, seeds and bounds; only the loops live here.
use glam::{Vec2, Vec3};
use tessera_core::bsdf::{Bsdf, BsdfTraits};
use tessera_core::sampling::warp::square_to_cosine_hemisphere;
use tessera_lab::stats::{sampled_albedo, sidak_alpha, Chi2Result, Pcg32, SphereChi2};

use crate::bsdf::{assert_chi2_passes, uniform_direction, CHI2_HALF};

/// Runs [`CHI2_HALF`] on each case `(label, bsdf, wi)` (case `k` with seed `first_seed + k`),
/// prints every result and asserts that all pass at the Šidák-corrected level of 0.01 over the
/// `n_tests` chi-square tests of the file, listing every failure.
pub fn assert_chi2_cases(
    cases: impl IntoIterator<Item = (String, Bsdf, Vec3)>,
    uv: Vec2,
    first_seed: u64,
    n_tests: usize,
) {
    let a = sidak_alpha(0.01, n_tests);
    let mut failed = Vec::new();
    for (k, (label, b, wi)) in cases.into_iter().enumerate() {
        let r = CHI2_HALF.run(&b, wi, uv, first_seed + k as u64);
        println!("{label}: {r}");
        if !r.passes(a) {
            failed.push(format!("{label}: {r}"));
        }
    }
    assert!(failed.is_empty(), "alpha = {a:.3e}:\n{}", failed.join("\n"));
}

/// Chi-square of the non-delta directions `drawn` samples from `wi` (its lobe choice from
/// `Pcg32::new(lobe_seed)`) against the density of `pdf_of`, on 20 x 40 cells with 500,000
/// samples and seed `seed`: the controls' wrong-density test, and its same-density twin.
pub fn chi2_against_density(
    drawn: &Bsdf,
    pdf_of: &Bsdf,
    wi: Vec3,
    uv: Vec2,
    lobe_seed: u64,
    seed: u64,
) -> Chi2Result {
    let mut rng = Pcg32::new(lobe_seed);
    SphereChi2 {
        theta_bins: 20,
        phi_bins: 40,
        samples: 500_000,
    }
    .run(
        |u| {
            let s = drawn.sample(wi, rng.next_f32(), u, uv)?;
            (!s.delta).then_some(s.wo)
        },
        |w| f64::from(pdf_of.pdf(wi, w, uv)),
        seed,
    )
}

/// Asserts, over 20,000 direction pairs, that `b` (named `label` in messages) gives finite,
/// non-negative `eval`, `pdf` and sample weights, and that at most 1 sample in 10^4 (rounding
/// near grazing angles, as many as `BsdfChi2` allows) disagrees with `pdf()` or has
/// `weight * pdf` unequal to `eval()` (relative 1e-3 plus 1e-6). The first `50 * grazing.len()`
/// incident directions and every third outgoing one cycle through `grazing`; the others, and
/// the sampler's inputs, come from `rng`.
pub fn assert_finite_and_consistent(
    b: &Bsdf,
    label: &str,
    grazing: &[Vec3],
    uv: Vec2,
    rng: &mut Pcg32,
) {
    let close = |a: f32, c: f32| (a - c).abs() <= 1e-3 * a.abs().max(c.abs()) + 1e-6;
    let (n, mut inconsistent) = (20_000, 0);
    for k in 0..n {
        let wi = if k < grazing.len() * 50 {
            grazing[k % grazing.len()]
        } else {
            uniform_direction(rng.next_vec2(), true)
        };
        let wo = if k % 3 == 0 {
            grazing[(k / 3) % grazing.len()]
        } else {
            uniform_direction(rng.next_vec2(), true)
        };
        let (f, p) = (b.eval(wi, wo, uv), b.pdf(wi, wo, uv));
        assert!(
            f.is_finite() && f.min_element() >= 0.0 && p.is_finite() && p >= 0.0,
            "{label}: wi {wi} wo {wo}: eval {f} pdf {p}"
        );
        if let Some(s) = b.sample(wi, rng.next_f32(), rng.next_vec2(), uv) {
            assert!(
                s.weight.is_finite() && s.weight.min_element() >= 0.0 && s.pdf > 0.0,
                "{label}: wi {wi}: {s:?}"
            );
            let (f, p) = (b.eval(wi, s.wo, uv), b.pdf(wi, s.wo, uv));
            let fw = s.weight * s.pdf;
            if !(close(s.pdf, p) && (0..3).all(|c| close(fw[c], f[c]))) {
                inconsistent += 1;
            }
        }
    }
    assert!(
        inconsistent <= n / 10_000,
        "{label}: {inconsistent} inconsistent samples"
    );
}

/// `integral eval(wi, wo) dwo` over the sphere by the midpoint rule on `nz x np` cells of
/// equal solid angle (uniform in `cos theta` and `phi`), first channel, in f64.
pub fn quadrature_albedo(b: &Bsdf, wi: Vec3, uv: Vec2, nz: usize, np: usize) -> f64 {
    let mut s = 0.0f64;
    for i in 0..nz {
        let z = -1.0 + 2.0 * (i as f64 + 0.5) / nz as f64;
        let r = (1.0 - z * z).max(0.0).sqrt();
        for j in 0..np {
            let p = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
            let wo = Vec3::new((r * p.cos()) as f32, (r * p.sin()) as f32, z as f32);
            s += f64::from(b.eval(wi, wo, uv).x);
        }
    }
    s * 4.0 * std::f64::consts::PI / (nz * np) as f64
}

/// The first channel's sampled albedo of a material (the mean sample weight, transmission
/// included) beside the quadrature of its `eval` over the sphere.
pub struct AlbedoAgreement {
    /// Mean sample weight.
    pub sampled: f64,
    /// Its standard error.
    pub se: f64,
    /// [`quadrature_albedo`] of `eval`.
    pub quadrature: f64,
}

impl AlbedoAgreement {
    /// `b`'s sampled albedo from `wi` (400,000 samples, seed 6) and the quadrature of its
    /// `eval` on 2000 x 400 cells.
    pub fn of(b: &Bsdf, wi: Vec3, uv: Vec2) -> Self {
        let (m, se) = sampled_albedo(b, wi, uv, 400_000, 6);
        AlbedoAgreement {
            sampled: f64::from(m.x),
            se: f64::from(se.x),
            quadrature: quadrature_albedo(b, wi, uv, 2000, 400),
        }
    }

    /// The two agree within 4 standard errors plus 1e-3 for the quadrature.
    pub fn agrees(&self) -> bool {
        (self.sampled - self.quadrature).abs() <= 4.0 * self.se + 1e-3
    }

    /// The two differ by more than 4 standard errors plus 1e-3 (what a control must show; a
    /// NaN neither agrees nor differs).
    pub fn differs(&self) -> bool {
        (self.sampled - self.quadrature).abs() > 4.0 * self.se + 1e-3
    }
}

impl std::fmt::Display for AlbedoAgreement {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(
            f,
            "sampled {:.5} +- {:.5}, quadrature {:.5}",
            self.sampled, self.se, self.quadrature
        )
    }
}

/// The control of a chi-square file: the directions `drawn` samples from `wi` are rejected
/// against the density of `claimed` (a wrong lobe probability) at the Šidák-corrected level of
/// 0.01 over the file's `n_tests` chi-square tests, and pass against their own density. Both
/// use [`chi2_against_density`] with lobe seed 99 and chi-square seed 7.
pub fn assert_wrong_density_rejected(
    drawn: &Bsdf,
    claimed: &Bsdf,
    wi: Vec3,
    uv: Vec2,
    n_tests: usize,
) {
    let alpha = sidak_alpha(0.01, n_tests);
    let r = chi2_against_density(drawn, claimed, wi, uv, 99, 7);
    println!("control: {r}");
    assert!(!r.passes(alpha), "control not rejected: {r}");
    let r = chi2_against_density(drawn, drawn, wi, uv, 99, 7);
    assert_chi2_passes("same directions, own density", &r, n_tests);
}

/// Largest violation of `f(wi, wo) = f(wo, wi)` (with `f = eval / cos theta_o`) over 20,000
/// front-side direction pairs (cosine-distributed from `Pcg32::new(seed)`, pairs with a cosine
/// under 0.02 skipped), relative to the larger value, or to `floor` where that is larger.
pub fn reciprocity_error(eval: impl Fn(Vec3, Vec3) -> Vec3, seed: u64, floor: f32) -> f32 {
    let mut rng = Pcg32::new(seed);
    let mut worst = 0.0f32;
    for _ in 0..20_000 {
        let a = square_to_cosine_hemisphere(rng.next_vec2());
        let b = square_to_cosine_hemisphere(rng.next_vec2());
        if a.z < 0.02 || b.z < 0.02 {
            continue;
        }
        let fab = eval(a, b) / b.z;
        let fba = eval(b, a) / a.z;
        let d = (fab - fba).abs().max_element() / fab.max(fba).max_element().max(floor);
        worst = worst.max(d);
    }
    worst
}

/// Asserts what the path loop is told about a material with smooth lobes only: it samples with
/// both inputs, is not Lambertian, reads no partials (not bump-mapped), no image and no texture
/// coordinates, and has no delta component.
pub fn assert_smooth_two_input_traits(b: &Bsdf) {
    assert_eq!(
        BsdfTraits::of(b),
        BsdfTraits {
            uses_u1: true,
            uses_u2: true,
            has_smooth: true,
            lambertian: false,
            reads_geometry: false,
            reads_images: false,
            reads_uv: false,
        }
    );
    assert!(!b.has_delta());
}

/// How many textures `b` reports reading.
pub fn texture_count(b: &Bsdf) -> usize {
    let mut n = 0;
    b.for_each_texture(&mut |_| n += 1);
    n
}

//! Microfacet normal distributions (Beckmann, GGX / Trowbridge-Reitz), anisotropic, with Smith
//! shadowing and two ways to sample a normal: all normals by `D(m) cos theta_m`, or only the
//! normals visible from a direction, by `G1(wi, m) max(0, wi.m) D(m) / cos theta_i` (Heitz 2014).
//!
//! Shared by `roughconductor`, `roughdielectric` and `roughplastic` (Mitsuba 3 parameter names:
//! `distribution` = beckmann | ggx, `alpha` or `alpha_u` / `alpha_v`, `sample_visible`).
//! Beckmann's Smith term uses the rational approximation of Walter et al. 2007, as Mitsuba 3 and
//! the Wakame assignment do. All directions are in the local frame (+z = macro normal).
use crate::math::{acos_f64, safe_sqrt, sincos_turns, sqrt, sqrt_f64, Norm, PI};
use glam::{Vec2, Vec3};

/// Which normal distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MicrofacetKind {
    /// Gaussian slopes.
    Beckmann,
    /// Trowbridge-Reitz (GGX): longer tails.
    Ggx,
}

/// An anisotropic microfacet distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// Distribution family.
    pub kind: MicrofacetKind,
    /// Roughness along the local x axis (> 0).
    pub alpha_u: f32,
    /// Roughness along the local y axis (> 0).
    pub alpha_v: f32,
    /// Whether `sample` draws only the normals visible from `wi`.
    pub sample_visible: bool,
}

impl Microfacet {
    /// An isotropic distribution with visible-normal sampling.
    pub fn new(kind: MicrofacetKind, alpha: f32) -> Self {
        Microfacet {
            kind,
            alpha_u: alpha,
            alpha_v: alpha,
            sample_visible: true,
        }
    }

    /// Normal density `D(m)` (per unit solid angle of `m`, normalised so that
    /// `integral D(m) cos theta_m dm = 1`).
    #[inline]
    pub fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let (ax, ay) = (self.alpha_u, self.alpha_v);
        let z2 = m.z * m.z;
        let e = (m.x / ax) * (m.x / ax) + (m.y / ay) * (m.y / ay);
        let r = match self.kind {
            MicrofacetKind::Beckmann => libm::expf(-e / z2) / (PI * ax * ay * z2 * z2),
            MicrofacetKind::Ggx => {
                let t = e + z2;
                1.0 / (PI * ax * ay * t * t)
            }
        };
        if r * m.z > 1e-20 && r.is_finite() {
            r
        } else {
            0.0
        }
    }

    /// Smith's masking term for direction `v` and microfacet normal `m`.
    #[inline]
    pub(crate) fn g1(&self, v: Vec3, m: Vec3) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let xy = (self.alpha_u * v.x) * (self.alpha_u * v.x)
            + (self.alpha_v * v.y) * (self.alpha_v * v.y);
        if xy == 0.0 {
            return 1.0;
        }
        let tan2 = xy / (v.z * v.z);
        match self.kind {
            MicrofacetKind::Beckmann => {
                let a = 1.0 / sqrt(tan2);
                if a >= 1.6 {
                    1.0
                } else {
                    (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
                }
            }
            MicrofacetKind::Ggx => 2.0 / (1.0 + sqrt(1.0 + tan2)),
        }
    }

    /// Separable shadowing-masking `G1(wi, m) G1(wo, m)`.
    #[inline]
    pub fn g(&self, wi: Vec3, wo: Vec3, m: Vec3) -> f32 {
        self.g1(wi, m) * self.g1(wo, m)
    }

    /// Density with which [`Microfacet::sample`] returns `m` for `wi` (`wi.z > 0`).
    #[inline]
    pub fn pdf(&self, wi: Vec3, m: Vec3) -> f32 {
        if self.sample_visible {
            if wi.z <= 0.0 {
                return 0.0;
            }
            self.d(m) * self.g1(wi, m) * wi.dot(m).abs() / wi.z
        } else {
            self.d(m) * m.z.max(0.0)
        }
    }

    /// Density of `wo`, the mirror of `wi` about the normal `h` drawn by [`Microfacet::sample`]
    /// (the Jacobian of the reflection, `1 / (4 wo.h)`, folded in).
    #[inline]
    pub(crate) fn reflected_pdf(&self, wi: Vec3, wo: Vec3, h: Vec3) -> f32 {
        if self.sample_visible {
            self.d(h) * self.g1(wi, h) / (4.0 * wi.z)
        } else {
            self.pdf(wi, h) / (4.0 * wo.dot(h))
        }
    }

    /// Samples a microfacet normal for `wi` (`wi.z > 0` when sampling visible normals); returns
    /// the normal and its density.
    #[inline]
    pub fn sample(&self, wi: Vec3, u: Vec2) -> Option<(Vec3, f32)> {
        let m = if self.sample_visible {
            if wi.z <= 0.0 {
                return None;
            }
            match self.kind {
                MicrofacetKind::Ggx => self.sample_visible_ggx(wi, u),
                MicrofacetKind::Beckmann => self.sample_visible_beckmann(wi, u),
            }
        } else {
            self.sample_all(u)
        };
        if !m.is_finite() || m.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(wi, m);
        (pdf > 0.0 && pdf.is_finite()).then_some((m, pdf))
    }

    /// A direction for a glossy lobe over a diffuse base: with probability `p_glossy` (chosen
    /// by `u1`) the mirror of `wi` about a sampled microfacet normal, else cosine-weighted.
    #[inline]
    pub(crate) fn sample_glossy_or_diffuse(
        &self,
        wi: Vec3,
        u1: f32,
        u2: Vec2,
        p_glossy: f32,
    ) -> Option<Vec3> {
        if u1 < p_glossy {
            let (m, _) = self.sample(wi, u2)?;
            Some(super::fresnel::reflect(wi, m))
        } else {
            Some(crate::sampling::warp::square_to_cosine_hemisphere(u2))
        }
    }

    /// All normals by `D(m) cos theta_m`: slopes drawn from the isotropic unit-roughness slope
    /// density, then stretched by the roughness.
    fn sample_all(&self, u: Vec2) -> Vec3 {
        let u1 = u.x.min(1.0 - f32::EPSILON);
        let r = match self.kind {
            MicrofacetKind::Beckmann => safe_sqrt(-libm::log1pf(-u1)),
            MicrofacetKind::Ggx => safe_sqrt(u1 / (1.0 - u1)),
        };
        let (s, c) = sincos_turns(u.y);
        Vec3::new(-r * c * self.alpha_u, -r * s * self.alpha_v, 1.0).unit()
    }

    /// Visible GGX normals: uniform on the projected hemisphere of the stretched configuration
    /// (Heitz 2018).
    fn sample_visible_ggx(&self, wi: Vec3, u: Vec2) -> Vec3 {
        let vh = Vec3::new(self.alpha_u * wi.x, self.alpha_v * wi.y, wi.z).unit();
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-vh.y, vh.x, 0.0) / sqrt(len2)
        } else {
            Vec3::X
        };
        let t2 = vh.cross(t1);
        let r = sqrt(u.x);
        let (sp, cp) = sincos_turns(u.y);
        let p1 = r * cp;
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * safe_sqrt(1.0 - p1 * p1) + s * r * sp;
        let nh = p1 * t1 + p2 * t2 + safe_sqrt(1.0 - p1 * p1 - p2 * p2) * vh;
        Vec3::new(self.alpha_u * nh.x, self.alpha_v * nh.y, nh.z.max(1e-7)).unit()
    }

    /// Visible Beckmann normals: the slope distribution of the visible normals for unit
    /// roughness is sampled in `x` by inverting its CDF (Newton-bisection on `erf`) and in `y`
    /// as a Gaussian, then rotated and stretched (Heitz and d'Eon 2014).
    fn sample_visible_beckmann(&self, wi: Vec3, u: Vec2) -> Vec3 {
        let w = Vec3::new(self.alpha_u * wi.x, self.alpha_v * wi.y, wi.z).unit();
        let sin_t = safe_sqrt(1.0 - w.z * w.z);
        let (cos_phi, sin_phi) = if sin_t > 1e-7 {
            (w.x / sin_t, w.y / sin_t)
        } else {
            (1.0, 0.0)
        };
        let (sx, sy) = beckmann_visible_slope(f64::from(w.z), f64::from(u.x), f64::from(u.y));
        let (sx, sy) = (sx as f32, sy as f32);
        let x = (cos_phi * sx - sin_phi * sy) * self.alpha_u;
        let y = (sin_phi * sx + cos_phi * sy) * self.alpha_v;
        Vec3::new(-x, -y, 1.0).unit()
    }
}

/// Slopes of a visible unit-roughness Beckmann normal for a direction with cosine `cos_t` in
/// the x-z plane, from two uniform numbers. Computed in f64.
fn beckmann_visible_slope(cos_t: f64, u1: f64, u2: f64) -> (f64, f64) {
    const INV_SQRT_PI: f64 = 0.5 * core::f64::consts::FRAC_2_SQRT_PI;
    let u1 = u1.clamp(1e-9, 1.0 - 1e-9);
    let u2 = u2.clamp(1e-9, 1.0 - 1e-9);
    if cos_t > 0.999_999 {
        let r = sqrt_f64(-libm::log(1.0 - u1));
        let (s, c) = libm::sincos(2.0 * core::f64::consts::PI * u2);
        return (r * c, r * s);
    }
    let sin_t = sqrt_f64((1.0 - cos_t * cos_t).max(0.0));
    let tan_t = sin_t / cos_t;
    let cot_t = 1.0 / tan_t;
    // The CDF of the x slope is (1 + erf(x) + tan_t exp(-x^2) / sqrt(pi)) / norm on
    // (-inf, cot_t), its density (2 / sqrt(pi)) exp(-x^2) (1 - x tan_t) / norm. Newton steps on
    // cdf(x) = u1, kept inside a shrinking bracket (bisection when a step leaves it); below
    // x = -6 the CDF is under 1e-15, so the bracket starts there. Each step costs an `erf` and
    // an `exp` (a step in the variable erf(x) would cost an inverse error function more).
    let erf_cot = libm::erf(cot_t);
    let norm = 1.0 / (1.0 + erf_cot + INV_SQRT_PI * tan_t * libm::exp(-cot_t * cot_t));
    let (mut lo, mut hi) = (-6.0f64, cot_t);
    // A fitted first guess of erf(x), as a power of 1 - u1.
    let theta = acos_f64(cos_t);
    let fit = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
    let b = erf_cot - (1.0 + erf_cot) * libm::exp(fit * libm::log(1.0 - u1));
    let mut x = erfinv_steps(b, false);
    for _ in 0..64 {
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        let e = libm::exp(-x * x);
        let value = norm * (1.0 + libm::erf(x) + INV_SQRT_PI * tan_t * e) - u1;
        if value.abs() < 1e-9 {
            break;
        }
        if value > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        x -= value / (norm * core::f64::consts::FRAC_2_SQRT_PI * e * (1.0 - x * tan_t));
    }
    (x, erfinv(2.0 * u2 - 1.0))
}

/// Inverse error function: Giles' approximation refined by Newton steps on `erf`.
pub fn erfinv(x: f64) -> f64 {
    erfinv_steps(x, true)
}

/// Giles' approximation of the inverse error function (relative error about 1e-7 in `erf`),
/// refined by Newton steps when `refine`.
fn erfinv_steps(x: f64, refine: bool) -> f64 {
    if x <= -1.0 {
        return f64::NEG_INFINITY;
    }
    if x >= 1.0 {
        return f64::INFINITY;
    }
    let mut w = -libm::log((1.0 - x) * (1.0 + x));
    let mut p;
    // In the central branch one Newton step takes the approximation's error (5e-8 in erf) to
    // below 5e-15; the tail branch (|x| > 0.9966) is coarser and keeps a second.
    let newton_steps = match (refine, w < 5.0) {
        (false, _) => 0,
        (true, true) => 1,
        (true, false) => 2,
    };
    if w < 5.0 {
        w -= 2.5;
        p = 2.810_226_36e-08;
        for c in [
            3.432_739_39e-07,
            -3.523_387_7e-06,
            -4.391_506_54e-06,
            2.185_808_7e-04,
            -1.253_725_03e-03,
            -4.177_681_64e-03,
            2.466_407_27e-01,
            1.501_409_41,
        ] {
            p = c + p * w;
        }
    } else {
        w = sqrt_f64(w) - 3.0;
        p = -2.002_142_57e-04;
        for c in [
            1.009_505_58e-04,
            1.349_343_22e-03,
            -3.673_428_44e-03,
            5.739_507_73e-03,
            -7.622_461_3e-03,
            9.438_870_47e-03,
            1.001_674_06,
            2.832_976_82,
        ] {
            p = c + p * w;
        }
    }
    let mut y = p * x;
    // Newton on erf(y) = x: derivative 2/sqrt(pi) exp(-y^2).
    for _ in 0..newton_steps {
        let d = core::f64::consts::FRAC_2_SQRT_PI * libm::exp(-y * y);
        if d > 0.0 {
            y -= (libm::erf(y) - x) / d;
        }
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The x slope solves cdf(x) = u1 to the solver's tolerance over the whole range of
    /// incident cosines (grazing to normal) and of `u1` (tails included), and the y slope is the
    /// Gaussian's. Control: the first guess alone (the fitted power of `1 - u1`) misses by far
    /// more.
    #[test]
    fn visible_beckmann_slope_inverts_its_cdf() {
        const INV_SQRT_PI: f64 = 0.5 * core::f64::consts::FRAC_2_SQRT_PI;
        let mut guess_worst = 0.0f64;
        for &cos_t in &[1e-4, 1e-3, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.9999] {
            let tan_t = sqrt_f64(1.0 - cos_t * cos_t) / cos_t;
            let cot_t = 1.0 / tan_t;
            let cdf = |x: f64| {
                let f = |x: f64| 1.0 + libm::erf(x) + INV_SQRT_PI * tan_t * libm::exp(-x * x);
                f(x) / f(cot_t)
            };
            for k in 0..=1000 {
                let u1 = (k as f64 / 1000.0).clamp(1e-9, 1.0 - 1e-9);
                let (x, y) = beckmann_visible_slope(cos_t, u1, 0.3);
                assert!(x <= cot_t && x > -6.0, "cos {cos_t} u {u1}: x {x}");
                assert!(
                    (cdf(x) - u1).abs() < 2e-9,
                    "cos {cos_t} u {u1}: cdf {}",
                    cdf(x)
                );
                assert!((libm::erf(y) - (2.0 * 0.3 - 1.0)).abs() < 1e-12);
                let theta = acos_f64(cos_t);
                let fit = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
                let erf_cot = libm::erf(cot_t);
                let b = erf_cot - (1.0 + erf_cot) * libm::pow(1.0 - u1, fit);
                guess_worst = guess_worst.max((cdf(erfinv(b)) - u1).abs());
            }
        }
        assert!(
            guess_worst > 1e-4,
            "control: the first guess is already exact"
        );
    }

    #[test]
    fn erfinv_inverts_erf() {
        for i in -9999..=9999 {
            let x = i as f64 / 10000.0;
            assert!((libm::erf(erfinv(x)) - x).abs() < 1e-13, "{x}");
        }
        for k in 3..=7 {
            let x = 1.0 - libm::pow(10.0, -f64::from(k));
            assert!((libm::erf(erfinv(x)) - x).abs() < 1e-13, "{x}");
            assert!((libm::erf(erfinv(-x)) + x).abs() < 1e-13, "{x}");
        }
    }

    #[test]
    fn d_is_normalised() {
        // integral of D(m) cos(theta_m) over the hemisphere = 1, by a midpoint rule in
        // (cos theta, phi).
        for kind in [MicrofacetKind::Beckmann, MicrofacetKind::Ggx] {
            let md = Microfacet {
                kind,
                alpha_u: 0.3,
                alpha_v: 0.6,
                sample_visible: true,
            };
            let (nt, np) = (2000, 200);
            let mut s = 0.0f64;
            for i in 0..nt {
                let z = (i as f32 + 0.5) / nt as f32;
                for j in 0..np {
                    let phi = 2.0 * PI * (j as f32 + 0.5) / np as f32;
                    let r = safe_sqrt(1.0 - z * z);
                    let m = Vec3::new(r * libm::cosf(phi), r * libm::sinf(phi), z);
                    s += f64::from(md.d(m) * z);
                }
            }
            s *= 2.0 * core::f64::consts::PI / (nt * np) as f64;
            assert!((s - 1.0).abs() < 2e-3, "{kind:?}: {s}");
        }
    }
}

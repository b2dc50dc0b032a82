//! Pieces shared by `plastic` and `roughplastic` (Mitsuba 3's coated-diffuse models): the
//! sampling weight between coating and base, the diffuse Fresnel reflectance of a smooth
//! interface, and the rough interface's tabulated transmittance and internal reflectance.
//!
//! The rough tables are computed the way Mitsuba 3 computes them when a `roughplastic` is built,
//! so that both renderers evaluate the same model: for 64 incident cosines `mu_i = max(1e-6,
//! i / 63)` the average over the normals visible from `wi = (sqrt(1 - mu^2), 0, mu)` of the
//! refracted energy `(1 - F(wi.m)) G1(wt, m)` (external transmittance) and of the reflected
//! energy `F(wi.m) G1(wr, m)` seen from inside (`eta -> 1/eta`), integrated with a tensor
//! Gauss-Legendre rule on the visible-normal sampler's unit square (32 x 32 nodes when the
//! relative index is above 1, else 128 x 128). The internal diffuse reflectance is then
//! `2 * mean_i(mu_i R(mu_i))`.
use super::fresnel::{fresnel_dielectric, reflect, refract};
use super::microfacet::{Microfacet, MicrofacetKind};
use crate::math::{safe_sqrt, sqrt, Norm};
use crate::sampling::warp::square_to_uniform_disk_concentric;
use crate::texture::Texture;
use alloc::boxed::Box;
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// Number of incident cosines in the rough transmittance table.
pub const TABLE_RES: usize = 64;

/// Diffuse Fresnel reflectance `Fdr`: the fraction of uniformly diffuse (cosine-weighted)
/// light reflected by a smooth interface of relative index `eta`, from the published fits
/// (Egan and Hilgeman 1973 for `eta < 1`, d'Eon and Irving 2011 otherwise), as Mitsuba 3 uses.
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    if eta < 1.0 {
        -1.4399 * (eta * eta) + 0.7099 * eta + 0.6681 + 0.0636 / eta
    } else {
        let i = 1.0 / eta;
        let (i2, i3) = (i * i, i * i * i);
        let (i4, i5) = (i3 * i, i3 * i2);
        0.919317 - 3.4793 * i + 6.75335 * i2 - 7.80989 * i3 + 4.98554 * i4 - 1.36881 * i5
    }
}

/// Mean value of a texture over the unit uv square (per channel, then over channels), by the
/// midpoint rule on a 64 x 64 grid: exact for constants.
pub(crate) fn texture_mean(t: &Texture) -> f32 {
    const N: usize = 64;
    let mut s = 0.0f64;
    for j in 0..N {
        for i in 0..N {
            let uv = Vec2::new((i as f32 + 0.5) / N as f32, (j as f32 + 0.5) / N as f32);
            s += f64::from(t.eval_1(uv));
        }
    }
    (s / (N * N) as f64) as f32
}

/// Mitsuba's `specular_sampling_weight`: `s_mean / (d_mean + s_mean)` (one half when both are
/// black, where the model reflects nothing anyway).
pub fn specular_sampling_weight(diffuse: &Texture, specular: &Texture) -> f32 {
    let (d, s) = (texture_mean(diffuse), texture_mean(specular));
    if d + s > 0.0 {
        s / (d + s)
    } else {
        0.5
    }
}

/// Probability of choosing the coating (specular) component given the coating's reflectance
/// `r` for the incident direction and the sampling weight `w`; `None` if neither component can
/// be chosen.
#[inline]
pub(crate) fn coating_probability(r: f32, w: f32) -> Option<f32> {
    let ps = r * w;
    let pd = (1.0 - r) * (1.0 - w);
    let sum = ps + pd;
    (sum > 0.0 && sum.is_finite()).then(|| ps / sum)
}

/// The base's diffuse reflectance after internal scattering: `d / (1 - Fdr_int)` (linear) or
/// `d / (1 - d Fdr_int)` per channel (nonlinear).
#[inline]
pub(crate) fn internal_scattering(d: glam::Vec3, fdr_int: f32, nonlinear: bool) -> glam::Vec3 {
    if nonlinear {
        d / (glam::Vec3::ONE - d * fdr_int)
    } else {
        d / (1.0 - fdr_int)
    }
}

/// Nodes and weights of the `n`-point Gauss-Legendre rule on `[-1, 1]` (Newton on the
/// Legendre recurrence, in f64).
pub(crate) fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    let nf = n as f64;
    for i in 0..n {
        // Initial guess (Tricomi), then Newton.
        let mut x = -libm::cos(core::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5));
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0f64, x);
            for k in 2..=n {
                let kf = k as f64;
                let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
                p0 = p1;
                p1 = p2;
            }
            // p1 = P_n(x), p0 = P_{n-1}(x).
            dp = nf * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// The rough coating's tables: external transmittance at the [`TABLE_RES`] cosines, and the
/// internal diffuse reflectance.
pub fn rough_tables(kind: MicrofacetKind, alpha: f32, eta: f32) -> (Box<[f32; TABLE_RES]>, f32) {
    let distr = Microfacet::new(kind, alpha);
    let rule_ext = UnitRule::new(if eta > 1.0 { 32 } else { 128 }, kind);
    let rule_int = UnitRule::new(if 1.0 / eta > 1.0 { 32 } else { 128 }, kind);
    let mut table = Box::new([0.0f32; TABLE_RES]);
    let mut internal = 0.0f64;
    for (i, t) in table.iter_mut().enumerate() {
        let mu = (i as f32 / (TABLE_RES - 1) as f32).max(1e-6);
        let wi = Vec3::new(sqrt(1.0 - mu * mu), 0.0, mu);
        *t = visible_integral(&distr, wi, &rule_ext, |m| {
            let fr = fresnel_dielectric(wi.dot(m), eta);
            let wt = refract(wi, m, fr.cos_t, fr.eta_ti);
            if wt.z * wi.z >= 0.0 {
                0.0
            } else {
                distr.g1(wt, m) * (1.0 - fr.f)
            }
        }) as f32;
        let r = visible_integral(&distr, wi, &rule_int, |m| {
            let wr = reflect(wi, m);
            if wr.z <= 0.0 {
                0.0
            } else {
                distr.g1(wr, m) * fresnel_dielectric(wi.dot(m), 1.0 / eta).f
            }
        });
        internal += r * f64::from(mu);
    }
    (table, (2.0 * internal / TABLE_RES as f64) as f32)
}

/// Gauss-Legendre rule on `[0, 1]`: points (f32, as the samplers take them) and weights, with
/// what the visible-normal map computes of the nodes alone, once for all incident cosines.
struct UnitRule {
    nodes: Vec<(f32, f64)>,
    /// GGX: the concentric-disk point of each node pair `(x, y)` (row-major in x) and
    /// `sqrt(1 - p.x^2)`. Empty for Beckmann.
    disk: Vec<(Vec2, f32)>,
}

impl UnitRule {
    fn new(n: usize, kind: MicrofacetKind) -> Self {
        let nodes: Vec<(f32, f64)> = gauss_legendre(n)
            .into_iter()
            .map(|(x, w)| ((0.5 * x + 0.5) as f32, 0.5 * w))
            .collect();
        let disk = match kind {
            MicrofacetKind::Beckmann => Vec::new(),
            MicrofacetKind::Ggx => nodes
                .iter()
                .flat_map(|&(ux, _)| nodes.iter().map(move |&(uy, _)| Vec2::new(ux, uy)))
                .map(|u| {
                    let p = square_to_uniform_disk_concentric(u);
                    (p, safe_sqrt(1.0 - p.x * p.x))
                })
                .collect(),
        };
        UnitRule { nodes, disk }
    }
}

/// Integral of `f(m)` over the normals visible from `wi` (in the x-z plane, `wi.x >= 0`), by
/// the tensor product of `rule` over the unit square mapped to visible normals. The map is
/// the same parameterisation of the square as Mitsuba 3 uses, so that the quadrature error
/// (Mitsuba's tables are themselves this quadrature) is the same: Jakob's (2014) numerical
/// inversion of the Beckmann visible-slope CDF (three Newton steps from the analytic guess for
/// grazing incidence), whose x and y slopes depend on one coordinate each, and Heitz's (2017)
/// concentric-disk construction for GGX. (The core's sampler parameterises GGX differently:
/// with these node counts its tables differ from Mitsuba's by up to 4e-4.)
fn visible_integral(distr: &Microfacet, wi: Vec3, rule: &UnitRule, f: impl Fn(Vec3) -> f32) -> f64 {
    let (disk, rule) = (&rule.disk, &rule.nodes[..]);
    let a = distr.alpha_u;
    let cos_t = wi.z / Vec3::new(a * wi.x, 0.0, wi.z).norm();
    let normal = |sx: f32, sy: f32| Vec3::new(-sx * a, -sy * a, 1.0).unit();
    let mut sum = 0.0;
    match distr.kind {
        MicrofacetKind::Beckmann => {
            let bv = BeckmannVisible::new(cos_t);
            let sy: Vec<f32> = rule.iter().map(|&(u, _)| erfinv(2.0 * u - 1.0)).collect();
            for &(ux, wx) in rule {
                let sx = bv.slope_x(ux);
                for (&(_, wy), &sy) in rule.iter().zip(&sy) {
                    sum += wx * wy * f64::from(f(normal(sx, sy)));
                }
            }
        }
        MicrofacetKind::Ggx => {
            let n = rule.len();
            for (i, &(_, wx)) in rule.iter().enumerate() {
                for (&(_, wy), &(p, sx)) in rule.iter().zip(&disk[i * n..(i + 1) * n]) {
                    let (sx, sy) = ggx_visible_slope(cos_t, p, sx);
                    sum += wx * wy * f64::from(f(normal(sx, sy)));
                }
            }
        }
    }
    sum
}

/// Jakob's Beckmann visible-slope inversion for unit roughness at incident cosine `cos_t`.
struct BeckmannVisible {
    tan_t: f32,
    max: f32,
    norm: f32,
}

impl BeckmannVisible {
    const INV_SQRT_PI: f32 = 0.564_189_6;

    fn new(cos_t: f32) -> Self {
        let tan_t = safe_sqrt(1.0 - cos_t * cos_t) / cos_t;
        let cot = 1.0 / tan_t;
        let max = libm::erff(cot);
        let norm = 1.0 + max + Self::INV_SQRT_PI * tan_t * libm::expf(-cot * cot);
        BeckmannVisible { tan_t, max, norm }
    }

    /// The x slope for the first sample coordinate (the y slope is `erfinv(2 u_y - 1)`).
    fn slope_x(&self, u: f32) -> f32 {
        let u = u.clamp(1e-6, 1.0 - 1e-6);
        let mut x = self.max - (self.max + 1.0) * libm::erff(sqrt(-libm::logf(u)));
        let target = u * self.norm;
        for _ in 0..3 {
            let s = erfinv(x);
            let value = 1.0 + x + Self::INV_SQRT_PI * self.tan_t * libm::expf(-s * s) - target;
            x -= value / (1.0 - s * self.tan_t);
        }
        erfinv(x)
    }
}

fn erfinv(x: f32) -> f32 {
    super::microfacet::erfinv(f64::from(x)) as f32
}

/// Heitz's (2017) GGX visible slope for unit roughness at incident cosine `cos_t`: a point `p`
/// of the concentric disk (with `sqrt_1mx2 = sqrt(1 - p.x^2)`), squeezed onto the visible half,
/// projected onto the hemisphere.
#[inline]
fn ggx_visible_slope(cos_t: f32, p: Vec2, sqrt_1mx2: f32) -> (f32, f32) {
    let s = 0.5 * (1.0 + cos_t);
    let x = p.x;
    let y = (1.0 - s) * sqrt_1mx2 + s * p.y;
    let z = safe_sqrt(1.0 - x * x - y * y);
    let sin_t = safe_sqrt(1.0 - cos_t * cos_t);
    let inv = 1.0 / (sin_t * y + cos_t * z);
    ((cos_t * y - sin_t * z) * inv, x * inv)
}

/// Linear interpolation in a table over `[0, 1]` (Mitsuba's `lerp_gather`).
#[inline]
pub(crate) fn lerp_table(table: &[f32; TABLE_RES], x: f32) -> f32 {
    let x = x * (TABLE_RES - 1) as f32;
    let i = (x.max(0.0) as usize).min(TABLE_RES - 2);
    let t = x - i as f32;
    table[i] * (1.0 - t) + table[i + 1] * t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials() {
        let g = gauss_legendre(8);
        let total: f64 = g.iter().map(|&(_, w)| w).sum();
        assert!((total - 2.0).abs() < 1e-12);
        // x^14 is exact for 8 points: integral 2/15.
        let s: f64 = g.iter().map(|&(x, w)| w * libm::pow(x, 14.0)).sum();
        assert!((s - 2.0 / 15.0).abs() < 1e-12, "{s}");
    }

    #[test]
    fn diffuse_fresnel_fits_are_continuous_near_one() {
        let a = fresnel_diffuse_reflectance(0.9999);
        let b = fresnel_diffuse_reflectance(1.0001);
        assert!(a.abs() < 3e-3 && b.abs() < 3e-3, "{a} {b}");
    }
}

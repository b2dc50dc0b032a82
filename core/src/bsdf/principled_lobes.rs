//! The building blocks of Mitsuba 3's `principled` BSDF (its `principledhelpers.h`, after
//! Burley's "Physically Based Shading at Disney", 2012): the clearcoat's GTR1 normal
//! distribution and its separable GGX masking, Schlick's weight and Fresnel approximation as
//! Mitsuba writes them, the blended metallic / tinted / dielectric Fresnel of the main lobe,
//! the side test between the macro and micro surfaces, and the roughness remapping.
//!
//! Directions are in the local frame (+z = macro normal) and point away from the surface.
use crate::math::{safe_sqrt, sincos_turns, sqrt, PI};
use crate::Color;
use glam::{Vec2, Vec3};

/// Luminance of a linear sRGB colour with Mitsuba 3's coefficients (its `luminance`).
#[inline]
pub fn luminance(c: Color) -> f32 {
    c.x * 0.212_671 + c.y * 0.715_160 + c.z * 0.072_169
}

/// `a + t (b - a)`, as Mitsuba's `dr::lerp`.
#[inline]
pub fn lerp(a: f32, b: f32, t: f32) -> f32 {
    b * t + (a - a * t)
}

/// `v` with its sign flipped where `s` is negative (Mitsuba's `dr::mulsign`, by sign bit).
#[inline]
pub fn mulsign(v: Vec3, s: f32) -> Vec3 {
    v * 1.0f32.copysign(s)
}

/// Schlick's weight `(1 - cos)^5`, with `1 - cos` clamped to `[0, 1]`.
#[inline]
pub(crate) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's Fresnel approximation with normal-incidence reflectance `r0`, at an interface of
/// relative index `eta` (inside over outside) seen with cosine `cos_i` against the micro
/// normal (negative from inside). When the incident side is the optically thinner one it
/// uses `cos_i`, else the refracted cosine (0, so full reflection, beyond the critical angle).
#[inline]
pub(crate) fn schlick_fresnel(r0: f32, cos_i: f32, eta: f32) -> f32 {
    let (eta_it, eta_ti) = if cos_i >= 0.0 {
        (eta, 1.0 / eta)
    } else {
        (1.0 / eta, eta)
    };
    let w = if eta_it > 1.0 {
        schlick_weight(cos_i.abs())
    } else {
        let cos_t = safe_sqrt(1.0 - (1.0 - cos_i * cos_i) * (eta_ti * eta_ti));
        schlick_weight(cos_t)
    };
    lerp(w, 1.0, r0)
}

/// Normal-incidence reflectance `((eta - 1) / (eta + 1))^2`.
#[inline]
pub(crate) fn schlick_r0(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// What the main lobe's Fresnel factor blends, at one point of the surface.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FresnelBlend {
    /// Metallic weight, `None` when the material has no `metallic`.
    pub metallic: Option<f32>,
    /// Specular tint weight, `None` when the material has no `spec_tint`.
    pub spec_tint: Option<f32>,
    /// The base colour.
    pub base_color: Color,
    /// Weight of the transmissive part, `(1 - metallic) spec_trans`.
    pub bsdf: f32,
    /// Relative index (inside over outside).
    pub eta: f32,
}

impl FresnelBlend {
    /// The main lobe's Fresnel factor for the true dielectric reflectance `f_dielectric` at
    /// micro cosine `cos_i`: from the front, the dielectric part weighted `(1 - metallic)
    /// (1 - spec_tint)` plus Schlick terms toward the base colour (`metallic`) and toward its
    /// hue (`spec_tint`); from the back, only the dielectric part of the transmissive weight.
    pub fn eval(&self, f_dielectric: f32, cos_i: f32, front: bool) -> Color {
        if !front {
            return Color::splat(self.bsdf * f_dielectric);
        }
        let m = self.metallic.unwrap_or(0.0);
        let tint = self.spec_tint.unwrap_or(0.0);
        let mut schlick = Color::ZERO;
        if self.metallic.is_some() {
            let c = self.base_color;
            schlick += m * Color::new(
                schlick_fresnel(c.x, cos_i, self.eta),
                schlick_fresnel(c.y, cos_i, self.eta),
                schlick_fresnel(c.z, cos_i, self.eta),
            );
        }
        if let Some(st) = self.spec_tint {
            let eta_it = if cos_i >= 0.0 {
                self.eta
            } else {
                1.0 / self.eta
            };
            let f0 = hue(self.base_color) * schlick_r0(eta_it);
            schlick += (1.0 - m)
                * st
                * Color::new(
                    schlick_fresnel(f0.x, cos_i, self.eta),
                    schlick_fresnel(f0.y, cos_i, self.eta),
                    schlick_fresnel(f0.z, cos_i, self.eta),
                );
        }
        Color::splat((1.0 - m) * (1.0 - tint) * f_dielectric) + schlick
    }
}

/// The colour divided by its luminance (white for a black colour): its hue at unit
/// luminance, toward which `spec_tint` and `sheen_tint` tint.
#[inline]
pub fn hue(c: Color) -> Color {
    let lum = luminance(c);
    if lum > 0.0 {
        c / lum
    } else {
        Color::ONE
    }
}

/// Whether micro normal `m` agrees with the macro surface for a reflection (`wi` and `wo` on
/// the side of `m` facing the incident side) or a refraction (`wo` on the other side).
#[inline]
pub(crate) fn micro_compatible(m: Vec3, wi: Vec3, wo: Vec3, cos_i: f32, reflection: bool) -> bool {
    let m = mulsign(m, cos_i);
    let o = wo.dot(m);
    wi.dot(m) > 0.0 && if reflection { o > 0.0 } else { o < 0.0 }
}

/// Burley's diffuse shape (Lambert's `1 / pi` and the cosine excluded): Schlick-weighted
/// diffuse `(1 - Fi / 2)(1 - Fo / 2)` plus retro-reflection `Rr (Fo + Fi + Fo Fi (Rr - 1))`
/// with `Rr = 2 roughness cos_d^2`, blended by `flatness` toward Hanrahan-Krueger's
/// flattened subsurface `1.25 (Fss (1 / (cos_o + cos_i) - 0.5) + 0.5)`. Cosines are absolute
/// (`ci`, `co`); `cos_d` is `wo.h`.
#[inline]
pub(crate) fn burley_diffuse(
    roughness: f32,
    flatness: Option<f32>,
    ci: f32,
    co: f32,
    cos_d: f32,
) -> f32 {
    let (fo, fi) = (schlick_weight(co), schlick_weight(ci));
    let f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    match flatness {
        Some(flat) => {
            let fss90 = rr / 2.0;
            let fss = lerp(1.0, fss90, fo) * lerp(1.0, fss90, fi);
            let f_ss = 1.25 * (fss * (1.0 / (co + ci) - 0.5) + 0.5);
            lerp(f_diff + f_retro, f_ss, flat)
        }
        None => f_diff + f_retro,
    }
}

/// The sheen's colour factor `Fd c_sheen` (weights and cosine excluded): Schlick's weight of
/// `cos_d` (`wo.h`), tinted toward the base colour's hue by `tint` when given.
#[inline]
pub(crate) fn sheen_color(tint: Option<f32>, base: Color, cos_d: f32) -> Color {
    let fd = schlick_weight(cos_d.abs());
    match tint {
        Some(t) => hue(base).map(|c| lerp(1.0, c, t)) * fd,
        None => Color::splat(fd),
    }
}

/// The main lobe's GGX roughnesses `(alpha_u, alpha_v)`: `roughness^2`, stretched by the
/// aspect `sqrt(1 - 0.9 anisotropic)` when the material has `anisotropic`; at least 1e-3.
#[inline]
pub(crate) fn main_alphas(roughness: f32, anisotropic: Option<f32>) -> (f32, f32) {
    let r2 = roughness * roughness;
    match anisotropic {
        None => {
            let a = r2.max(0.001);
            (a, a)
        }
        Some(an) => {
            let aspect = sqrt(1.0 - 0.9 * an);
            ((r2 / aspect).max(0.001), (r2 * aspect).max(0.001))
        }
    }
}

/// The clearcoat's roughness for a gloss in `[0, 1]`: from 0.1 (gloss 0) to 0.001 (gloss 1).
#[inline]
pub(crate) fn clearcoat_alpha(gloss: f32) -> f32 {
    lerp(0.1, 0.001, gloss)
}

/// Burley's isotropic GTR1 ("generalized Trowbridge-Reitz", exponent 1) normal distribution
/// of the clearcoat, with roughness `alpha` in `(0, 1)`.
#[derive(Clone, Copy, Debug)]
pub struct Gtr1 {
    /// Roughness.
    pub alpha: f32,
}

impl Gtr1 {
    /// `D(m) = (a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1) cos^2 theta_m))`, 0 below the horizon.
    #[inline]
    pub fn d(&self, m: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        let c = m.z;
        let r = (a2 - 1.0) / (PI * libm::logf(a2) * (1.0 + (a2 - 1.0) * c * c));
        if r * c > 1e-20 {
            r
        } else {
            0.0
        }
    }

    /// Density of [`Gtr1::sample`]: `D(m) cos theta_m`.
    #[inline]
    pub fn pdf(&self, m: Vec3) -> f32 {
        if m.z < 0.0 {
            0.0
        } else {
            m.z * self.d(m)
        }
    }

    /// A normal drawn by `D(m) cos theta_m` (inverting its CDF in `cos^2 theta`).
    #[inline]
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let (sin_phi, cos_phi) = sincos_turns(u.x);
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - libm::powf(a2, 1.0 - u.y)) / (1.0 - a2);
        let sin_t = safe_sqrt(1.0 - cos2);
        let cos_t = safe_sqrt(cos2);
        Vec3::new(cos_phi * sin_t, sin_phi * sin_t, cos_t)
    }
}

/// Smith's masking of an isotropic GGX with roughness `alpha` for direction `v` and micro
/// normal `m` (the clearcoat's, with `alpha` 0.25): 1 at normal incidence, 0 when `v` sees
/// the back of `m`.
#[inline]
pub(crate) fn smith_ggx1(v: Vec3, m: Vec3, alpha: f32) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let c2 = v.z * v.z;
    let tan2 = (1.0 - c2) / c2;
    2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2))
}

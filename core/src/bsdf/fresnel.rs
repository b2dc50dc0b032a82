//! Fresnel equations and the mirror / refraction directions shared by the specular and
//! microfacet models. All directions are unit vectors pointing away from the surface.
use crate::math::{safe_sqrt, sqrt};
use crate::Color;
use glam::Vec3;

/// Unpolarised Fresnel reflectance of a dielectric interface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricFresnel {
    /// Reflectance in `[0, 1]` (1 under total internal reflection).
    pub f: f32,
    /// Signed cosine of the refracted direction: opposite in sign to `cos_i`, 0 under total
    /// internal reflection.
    pub cos_t: f32,
    /// Relative index `eta_t / eta_i` seen by the incident side.
    pub eta_it: f32,
    /// Its inverse, `eta_i / eta_t`.
    pub eta_ti: f32,
}

/// Fresnel reflectance at an interface with relative index `eta` (inside over outside) for an
/// incident cosine `cos_i` measured against the normal that points outside; `cos_i < 0` means the
/// light arrives from inside.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> DielectricFresnel {
    let outside = cos_i >= 0.0;
    let (eta_it, eta_ti) = if outside {
        (eta, 1.0 / eta)
    } else {
        (1.0 / eta, eta)
    };
    if eta == 1.0 {
        return DielectricFresnel {
            f: 0.0,
            cos_t: -cos_i,
            eta_it,
            eta_ti,
        };
    }
    let ci = cos_i.abs();
    let cos_t_sqr = 1.0 - eta_ti * eta_ti * (1.0 - ci * ci);
    if cos_t_sqr <= 0.0 {
        return DielectricFresnel {
            f: 1.0,
            cos_t: 0.0,
            eta_it,
            eta_ti,
        };
    }
    let ct = sqrt(cos_t_sqr);
    let rs = (ci - eta_it * ct) / (ci + eta_it * ct);
    let rp = (eta_it * ci - ct) / (eta_it * ci + ct);
    let f = (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0);
    DielectricFresnel {
        f,
        cos_t: if outside { -ct } else { ct },
        eta_it,
        eta_ti,
    }
}

/// Unpolarised Fresnel reflectance of a conductor with complex index `eta + i k` (per channel)
/// for the incident cosine `cos_i` (its absolute value is used).
#[inline]
pub fn fresnel_conductor(cos_i: f32, eta: Color, k: Color) -> Color {
    let c = cos_i.abs().min(1.0);
    let ch = |e: f32, k: f32| -> f32 {
        let cos2 = c * c;
        let sin2 = 1.0 - cos2;
        let t0 = e * e - k * k - sin2;
        let a2b2 = safe_sqrt(t0 * t0 + 4.0 * e * e * k * k);
        let a = safe_sqrt(0.5 * (a2b2 + t0));
        let t1 = a2b2 + cos2;
        let t2 = 2.0 * c * a;
        let rs = if t1 + t2 > 0.0 {
            (t1 - t2) / (t1 + t2)
        } else {
            1.0
        };
        let t3 = cos2 * a2b2 + sin2 * sin2;
        let t4 = t2 * sin2;
        let rp = if t3 + t4 > 0.0 {
            rs * (t3 - t4) / (t3 + t4)
        } else {
            rs
        };
        (0.5 * (rs + rp)).clamp(0.0, 1.0)
    };
    Color::new(ch(eta.x, k.x), ch(eta.y, k.y), ch(eta.z, k.z))
}

/// Schlick's approximation `r0 + (1 - r0)(1 - cos)^5`.
#[inline]
pub(crate) fn schlick(r0: f32, cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    r0 + (1.0 - r0) * m2 * m2 * m
}

/// Mirror of `wi` about the unit normal `m`.
#[inline]
pub fn reflect(wi: Vec3, m: Vec3) -> Vec3 {
    2.0 * wi.dot(m) * m - wi
}

/// Refraction of `wi` through the interface with unit normal `m`, given `cos_t` and `eta_ti`
/// from [`fresnel_dielectric`] (evaluated with `cos_i = wi.m`).
#[inline]
pub(crate) fn refract(wi: Vec3, m: Vec3, cos_t: f32, eta_ti: f32) -> Vec3 {
    m * (wi.dot(m) * eta_ti + cos_t) - wi * eta_ti
}

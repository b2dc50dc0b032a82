//! The SGGX microflake phase function (`sggx`, Heitz, Dupuy, Crassin and Dachsbacher 2015), as
//! Mitsuba 3 defines it: the medium is made of tiny mirror flakes whose normals follow the SGGX
//! distribution of a symmetric positive definite matrix `S` (the normals of an ellipsoid).
//!
//! - Distribution of normals: `D(m) = 1 / (pi sqrt(det S) (m^T S^-1 m)^2)`.
//! - Projected area seen from `w`: `sigma(w) = sqrt(w^T S w)`. A medium with this phase function
//!   has extinction `sigma_t sigma(w)` along direction `w` (its media apply the factor), so
//!   fibres (`S = s^2 t t^T + (I - t t^T)`, thin along `t`) block less light along their axis.
//! - Scattering from `wi` to `wo` is a mirror reflection on a flake whose normal is the half
//!   vector `h = normalize(wi + wo)`: `f(wi, wo) = D(h) / (4 sigma(wi))`, normalised over the
//!   sphere for every `wi`.
//! - Sampling draws a normal from the distribution of normals visible from `wi` (the paper's
//!   construction from a cosine-distributed point in a frame around `wi`) and reflects `wi` on
//!   it; the density of the result is `f` itself, so the weight is 1.
//!
//! `S` comes from a 6-channel grid (`xx, yy, zz, xy, xz, yz`); the medium looks it up at the
//! scattering point and hands this function the matrix there. Keeping `S` positive definite is
//! the scene's duty, as in Mitsuba 3; a matrix that is not gives zero density.
use super::phase_sample::PhaseSample;
use crate::math::{sqrt, Frame, Norm, PI};
use crate::sampling::warp::square_to_cosine_hemisphere;
use core::ops::{Add, Mul};
use glam::{Vec2, Vec3};

/// A symmetric 3x3 matrix: its diagonal `(xx, yy, zz)` and off-diagonal `(xy, xz, yz)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SggxMatrix {
    /// `(S_xx, S_yy, S_zz)`.
    pub diag: Vec3,
    /// `(S_xy, S_xz, S_yz)`.
    pub off: Vec3,
}

impl Add for SggxMatrix {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        SggxMatrix {
            diag: self.diag + o.diag,
            off: self.off + o.off,
        }
    }
}

impl Mul<f32> for SggxMatrix {
    type Output = Self;
    #[inline]
    fn mul(self, k: f32) -> Self {
        SggxMatrix {
            diag: self.diag * k,
            off: self.off * k,
        }
    }
}

impl SggxMatrix {
    /// From the six values in Mitsuba's channel order `xx, yy, zz, xy, xz, yz`.
    #[inline]
    pub fn from_channels(c: [f32; 6]) -> Self {
        SggxMatrix {
            diag: Vec3::new(c[0], c[1], c[2]),
            off: Vec3::new(c[3], c[4], c[5]),
        }
    }
    /// `S v`.
    #[inline]
    fn apply(&self, v: Vec3) -> Vec3 {
        let (d, o) = (self.diag, self.off);
        Vec3::new(
            d.x * v.x + o.x * v.y + o.y * v.z,
            o.x * v.x + d.y * v.y + o.z * v.z,
            o.y * v.x + o.z * v.y + d.z * v.z,
        )
    }
    /// `a^T S b`.
    #[inline]
    fn form(&self, a: Vec3, b: Vec3) -> f32 {
        a.dot(self.apply(b))
    }
    /// The determinant.
    #[inline]
    pub fn det(&self) -> f32 {
        let (d, o) = (self.diag, self.off);
        d.x * d.y * d.z - d.x * o.z * o.z - d.y * o.y * o.y - d.z * o.x * o.x
            + 2.0 * o.x * o.y * o.z
    }
    /// The projected area of the flakes seen from unit direction `w`: `sqrt(w^T S w)` (the
    /// same for `-w`).
    #[inline]
    pub fn projected_area(&self, w: Vec3) -> f32 {
        sqrt(self.form(w, w).max(0.0))
    }
    /// An upper bound on the projected area over all unit directions: the square root of the
    /// largest row sum of absolute values, which bounds the largest eigenvalue (Gershgorin).
    pub fn projected_area_bound(&self) -> f32 {
        let (d, o) = (self.diag.abs(), self.off.abs());
        let rows = [d.x + o.x + o.y, d.y + o.x + o.z, d.z + o.y + o.z];
        sqrt(rows[0].max(rows[1]).max(rows[2]))
    }
    /// The density of normals `D(m)` at unit vector `m`.
    #[inline]
    pub fn ndf(&self, m: Vec3) -> f32 {
        let (d, o) = (self.diag, self.off);
        let det = self.det();
        if !(det > 0.0) {
            return 0.0;
        }
        // m^T adj(S) m = det * m^T S^-1 m.
        let q = m.x * m.x * (d.y * d.z - o.z * o.z)
            + m.y * m.y * (d.x * d.z - o.y * o.y)
            + m.z * m.z * (d.x * d.y - o.x * o.x)
            + 2.0
                * (m.x * m.y * (o.y * o.z - d.z * o.x)
                    + m.x * m.z * (o.x * o.z - d.y * o.y)
                    + m.y * m.z * (o.x * o.y - d.x * o.z));
        if !(q > 0.0) {
            return 0.0;
        }
        det * sqrt(det) / (PI * q * q)
    }
}

/// The SGGX phase function for one matrix (the one at the scattering point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sggx {
    /// The flakes' matrix.
    pub s: SggxMatrix,
}

impl Sggx {
    /// Value (and density) of scattering from `wi` toward `wo`.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        let h = wi + wo;
        let len = h.norm();
        let area = self.s.projected_area(wi);
        if !(len > 0.0) || !(area > 0.0) {
            return 0.0;
        }
        0.25 * self.s.ndf(h / len) / area
    }
    /// Samples `wo` for `wi` from two uniform numbers.
    pub fn sample(&self, wi: Vec3, u: Vec2) -> PhaseSample {
        let frame = Frame::from_normal(wi);
        let e = [frame.s, frame.t, wi];
        // S in the frame (k, j, i) = (s, t, wi).
        let m = |a: usize, b: usize| self.s.form(e[a], e[b]);
        let (sjj, sii) = (m(1, 1), m(2, 2));
        let (skj, ski, sji) = (m(0, 1), m(0, 2), m(1, 2));
        // A rotation keeps the determinant.
        let det = self.s.det();
        let tmp = sqrt((sjj * sii - sji * sji).max(0.0));
        let failed = PhaseSample {
            wo: Vec3::ZERO,
            pdf: 0.0,
            weight: 0.0,
        };
        if !(sii > 0.0) || !(tmp > 0.0) {
            return failed;
        }
        let inv_sqrt_sii = 1.0 / sqrt(sii);
        let mk = Vec3::new(sqrt(det.abs()) / tmp, 0.0, 0.0);
        let mj = Vec3::new(
            -inv_sqrt_sii * (ski * sji - skj * sii) / tmp,
            inv_sqrt_sii * tmp,
            0.0,
        );
        let mi = Vec3::new(ski, sji, sii) * inv_sqrt_sii;
        let c = square_to_cosine_hemisphere(u);
        let n_local = (mk * c.x + mj * c.y + mi * c.z).unit_or_zero();
        let n = e[0] * n_local.x + e[1] * n_local.y + e[2] * n_local.z;
        let wo = (n * (2.0 * wi.dot(n)) - wi).unit_or_zero();
        let pdf = self.eval(wi, wo);
        if !(pdf > 0.0) {
            return failed;
        }
        PhaseSample {
            wo,
            pdf,
            weight: 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fibre() -> SggxMatrix {
        SggxMatrix::from_channels([1.0, 0.35, 0.32, 0.52, 0.44, 0.2])
    }

    #[test]
    fn the_ndf_integrates_to_the_projected_area() {
        // Integral over the sphere of max(0, w.m) D(m) dm = sigma(w).
        let s = fibre();
        let w = Vec3::new(0.3, -0.5, 0.81).unit();
        let n = 400;
        let mut sum = 0.0f64;
        for i in 0..n {
            let ct = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let st = sqrt(1.0 - ct * ct);
            for j in 0..2 * n {
                let phi = PI * (j as f32 + 0.5) / n as f32;
                let m = Vec3::new(st * libm::cosf(phi), st * libm::sinf(phi), ct);
                sum += (w.dot(m).max(0.0) * s.ndf(m)) as f64;
            }
        }
        let integral = sum * (4.0 * PI as f64) / (2 * n * n) as f64;
        let area = s.projected_area(w) as f64;
        assert!(
            (integral - area).abs() < 1e-3 * area,
            "{integral} vs {area}"
        );
    }

    #[test]
    fn the_bound_bounds_every_direction() {
        let s = fibre();
        let b = s.projected_area_bound();
        for i in 0..1000 {
            let ct = 1.0 - 2.0 * (i as f32 + 0.5) / 1000.0;
            let st = sqrt(1.0 - ct * ct);
            let phi = 2.399_963 * i as f32;
            let w = Vec3::new(st * libm::cosf(phi), st * libm::sinf(phi), ct);
            assert!(s.projected_area(w) <= b);
        }
    }

    #[test]
    fn a_sample_reports_the_value_as_its_density() {
        let p = Sggx { s: fibre() };
        let wi = Vec3::new(0.2, 0.7, -0.4).unit();
        for k in 0..64 {
            let u = Vec2::new(
                (k as f32 + 0.5) / 64.0,
                ((k * 37) % 64) as f32 / 64.0 + 0.004,
            );
            let s = p.sample(wi, u);
            assert!(s.pdf > 0.0);
            assert!((s.pdf - p.eval(wi, s.wo)).abs() <= 1e-5 * s.pdf);
            assert!((s.wo.norm() - 1.0).abs() < 1e-5);
        }
    }
}

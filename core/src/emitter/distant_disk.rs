//! Distant disk: a disk-shaped light at infinity (a sun), seen by rays that escape the scene
//! within a half angle of its central direction. The Wakame assignment's `distantdisk`.
//!
//! Scene parameters (`<emitter type="distantdisk">`): `radiance` (rgb, required), `thetaA` (Nori
//! name; `theta_a` in Mitsuba 3 spelling: float, degrees, in (0, 180], required: the half angle
//! the disk subtends), `toWorld` / `to_world` (transform, default identity; a rotation,
//! optionally uniformly scaled: the disk's centre is in its local +z direction).
//!
//! Radiance is `radiance` for escaping directions within `thetaA` of the axis, 0 elsewhere; at
//! 180 degrees it is a constant environment. Sampled uniformly over the spherical cap (density
//! `1 / (2 pi (1 - cos thetaA))`); `1 - cos` is kept as `2 sin^2(thetaA / 2)` so tiny disks stay
//! exact. For light selection by power it counts as `pi r^2 * 2 pi (1 - cos thetaA) * L` (the
//! radiance of the cap falling on the disk of the scene's bounding sphere).
use super::sample::EmitterSample;
use crate::geometry::Interaction;
use crate::math::{Norm, PI};
use crate::sampling::warp::square_to_uniform_cone_omc;
use crate::Color;
use glam::{Mat3, Vec2, Vec3};

/// A disk light at infinity.
#[derive(Clone, Debug)]
pub struct DistantDisk {
    /// Radiance of the disk.
    pub radiance: Color,
    /// Local (axis +z) to world directions: a rotation.
    pub to_world: Mat3,
    /// World to local: the transpose of `to_world`.
    pub to_local: Mat3,
    /// `1 - cos(thetaA)`, in (0, 2].
    pub omc_max: f32,
}

impl DistantDisk {
    /// A disk of half angle `theta_a_deg` degrees (in (0, 180]) around `to_world`'s +z;
    /// `to_world` must be a rotation (the caller checks).
    pub fn new(radiance: Color, theta_a_deg: f32, to_world: Mat3) -> Self {
        let omc_max = if theta_a_deg >= 180.0 {
            2.0
        } else {
            let s = libm::sinf(0.5 * theta_a_deg.to_radians());
            (2.0 * s * s).clamp(f32::MIN_POSITIVE, 2.0)
        };
        DistantDisk {
            radiance,
            to_world,
            to_local: to_world.transpose(),
            omc_max,
        }
    }

    /// Whether the world direction `d` (unit) points into the disk.
    #[inline]
    fn inside(&self, d: Vec3) -> bool {
        if self.omc_max >= 2.0 {
            return true;
        }
        let l = (self.to_local * d).unit_or_zero();
        // 1 - cos(theta) without cancellation near the axis.
        let omc = if l.z >= 0.0 {
            (l.x * l.x + l.y * l.y) / (1.0 + l.z)
        } else {
            1.0 - l.z
        };
        omc <= self.omc_max
    }

    /// Radiance arriving along the escaping unit direction `d`.
    #[inline]
    pub fn eval(&self, d: Vec3) -> Color {
        if self.inside(d) {
            self.radiance
        } else {
            Color::ZERO
        }
    }

    /// Solid-angle density of `sample` for direction `d`.
    #[inline]
    pub fn pdf(&self, d: Vec3) -> f32 {
        if self.inside(d) {
            self.uniform_pdf()
        } else {
            0.0
        }
    }

    #[inline]
    fn uniform_pdf(&self) -> f32 {
        1.0 / (2.0 * PI * self.omc_max)
    }

    /// A direction uniform over the disk's cap.
    pub fn sample(&self, _it: &Interaction, u: Vec2) -> Option<EmitterSample> {
        let local = square_to_uniform_cone_omc(u, self.omc_max);
        let wo = (self.to_world * local).unit_or_zero();
        if wo == Vec3::ZERO {
            return None;
        }
        let pdf = self.uniform_pdf();
        Some(EmitterSample {
            wo,
            target: None,
            weight: self.radiance / pdf,
            pdf,
            delta: false,
        })
    }

    /// Solid angle of the disk (sr).
    pub(crate) fn solid_angle(&self) -> f32 {
        2.0 * PI * self.omc_max
    }
}

//! Analytic sphere.
//!
//! Scene parameters (`<shape type="sphere">`): `center` (point, default 0,0,0), `radius` (float,
//! default 1), `to_world` (transform: a uniform scale, rotation and translation of the unit sphere;
//! combined with center/radius), `flip_normals` (boolean, default false). Normals point outward
//! unless flipped.
use crate::math::{gamma, safe_sqrt, sincos_turns, sqrt, Frame, Norm, Ray, PI};
use glam::{Vec2, Vec3};

/// A sphere in world space.
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius (> 0).
    pub radius: f32,
}

/// A point on a sphere seen from a reference point, sampled by solid angle.
#[derive(Clone, Copy, Debug)]
pub struct ConeSample {
    /// Point on the sphere.
    pub p: Vec3,
    /// Error bound of `p` (the bound [`Sphere::project`] gives a point it places on the sphere).
    pub p_err: Vec3,
    /// Outward unit normal there.
    pub n: Vec3,
    /// Solid-angle density at the reference point.
    pub pdf: f32,
}

impl Sphere {
    /// Surface area.
    pub fn area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    /// Nearest intersection in `(t_err, t_max)`, as the ray parameter `t`.
    ///
    /// Uses the cancellation-free form of Ray Tracing Gems ch. 7 on the normalized direction,
    /// and rejects roots smaller than their own error bound (the origin sits on this sphere).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let len = ray.d.norm();
        if !(len > 0.0) {
            return None;
        }
        let d = ray.d / len;
        let f = ray.o - self.center;
        let r2 = self.radius * self.radius;
        let b = -f.dot(d);
        let l = f + d * b;
        let disc = r2 - l.length_squared();
        if disc < 0.0 {
            return None;
        }
        let c = f.length_squared() - r2;
        let q = b + libm::copysignf(sqrt(disc), b);
        if q == 0.0 {
            return None;
        }
        let (mut t0, mut t1) = (c / q, q);
        if t0 > t1 {
            core::mem::swap(&mut t0, &mut t1);
        }
        let t_err = gamma(8) * (f.length_squared() + r2) / q.abs() + gamma(4) * f.norm();
        let t_max_n = t_max * len;
        for t in [t0, t1] {
            if t > t_err && t < t_max_n {
                return Some(t / len);
            }
        }
        None
    }

    /// Re-projects a point near the surface onto it; returns the point and its error bound.
    #[inline]
    pub fn project(&self, p: Vec3) -> (Vec3, Vec3) {
        let v = p - self.center;
        let len = v.norm();
        let v = if len > 0.0 {
            v * (self.radius / len)
        } else {
            Vec3::new(0.0, 0.0, self.radius)
        };
        let p = self.center + v;
        let err = v.abs() * gamma(5) + self.center.abs() * gamma(2);
        (p, err)
    }

    /// Whether `r` is clearly outside: farther from the centre than the radius plus the
    /// rounding error a point of this sphere carries (that of [`Sphere::project`], which grows
    /// with the distance of the centre from the origin). A point on the sphere itself (a flipped
    /// emitting sphere lighting its own inside) is thus never taken for an outside one, at any
    /// scale or offset. Returns the squared distance to the centre.
    #[inline]
    fn outside(&self, r: Vec3) -> Option<f32> {
        let dist2 = (self.center - r).length_squared();
        let slack = gamma(16) * (self.radius + self.center.abs().max_element());
        let limit = self.radius + slack;
        (dist2 > limit * limit).then_some(dist2)
    }

    /// Samples the part of the sphere visible from `r` uniformly in solid angle (the cone of
    /// directions toward it); `None` when `r` is inside or on the sphere (within rounding), where
    /// callers sample by area instead.
    ///
    /// The direction's angle `theta` from the axis `r -> centre` is drawn by solid angle, then
    /// the point is placed directly by its angle `alpha` at the centre (the near root of the
    /// triangle `r`, centre, point), `cos alpha = sin^2 theta / sin theta_max + cos theta *
    /// sqrt(1 - sin^2 theta / sin^2 theta_max)`: no ray-sphere intersection and no re-projection
    /// of an intersection point, which made a long chain of square roots and divisions.
    pub fn sample_cone(&self, r: Vec3, u: Vec2) -> Option<ConeSample> {
        let dc = self.center - r;
        let dist2 = self.outside(r)?;
        let cone = Cone::new(self.radius, dist2);
        // 1 - cos theta, and sin^2 theta / sin^2 theta_max = u.x (2 - omc) / (1 + cos theta_max),
        // which stays accurate for the tiny cones of far spheres.
        let omc = u.x * cone.omc;
        let cos_t = 1.0 - omc;
        let ratio = (u.x * (2.0 - omc) * cone.inv_one_plus_cos).min(1.0);
        let inv_dist = 1.0 / sqrt(dist2);
        let sin_max = self.radius * inv_dist;
        let cos_a = (ratio * sin_max + cos_t * safe_sqrt(1.0 - ratio)).min(1.0);
        let sin_a = safe_sqrt(1.0 - cos_a * cos_a);
        let (s, c) = sincos_turns(u.y);
        let frame = Frame::from_normal(dc * inv_dist);
        // The outward normal leans back toward `r` by alpha from the axis.
        let n = frame
            .to_world(Vec3::new(sin_a * c, sin_a * s, -cos_a))
            .unit_or(-frame.n);
        let v = n * self.radius;
        // `n` is unit up to a few rounding steps per component, so `p` sits on the sphere within
        // the bound of [`Sphere::project`] (per-component relative error of `v`, then the sum).
        let p = self.center + v;
        let p_err = v.abs() * gamma(6) + self.center.abs() * gamma(2);
        Some(ConeSample {
            p,
            p_err,
            n,
            pdf: cone.pdf(),
        })
    }

    /// Solid-angle density of [`Sphere::sample_cone`] from `r`, or `None` when `r` is inside or
    /// on the sphere.
    pub fn cone_pdf(&self, r: Vec3) -> Option<f32> {
        let dist2 = self.outside(r)?;
        Some(Cone::new(self.radius, dist2).pdf())
    }
}

/// The cone of directions from a point at squared distance `dist2` from the centre of a sphere
/// of radius `radius`: what [`Sphere::sample_cone`] and [`Sphere::cone_pdf`] share, so their
/// densities are the same bits.
struct Cone {
    /// `1 - cos theta_max`, as `sin^2 / (1 + cos)` (exact for tiny cones).
    omc: f32,
    /// `1 / (1 + cos theta_max)`.
    inv_one_plus_cos: f32,
}

impl Cone {
    #[inline]
    fn new(radius: f32, dist2: f32) -> Cone {
        let sin2 = radius * radius / dist2;
        let inv_one_plus_cos = 1.0 / (1.0 + safe_sqrt(1.0 - sin2));
        Cone {
            omc: sin2 * inv_one_plus_cos,
            inv_one_plus_cos,
        }
    }
    /// Uniform density over the cone's solid angle, `1 / (2 pi (1 - cos theta_max))`.
    #[inline]
    fn pdf(&self) -> f32 {
        1.0 / (2.0 * PI * self.omc)
    }
}

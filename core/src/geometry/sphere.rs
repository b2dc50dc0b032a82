//! Analytic sphere.
//!
//! Scene parameters (`<shape type="sphere">`): `center` (point, default 0,0,0), `radius` (float,
//! default 1), `to_world` (transform: a uniform scale, rotation and translation of the unit sphere;
//! combined with center/radius), `flip_normals` (boolean, default false). Normals point outward
//! unless flipped.
use crate::math::{gamma, safe_sqrt, Frame, Ray, PI};
use crate::sampling::warp::square_to_uniform_cone_omc;
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
    /// Error bound of `p` (from its projection onto the sphere, [`Sphere::project`]).
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
        let len = ray.d.length();
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
        let q = b + libm::copysignf(libm::sqrtf(disc), b);
        if q == 0.0 {
            return None;
        }
        let (mut t0, mut t1) = (c / q, q);
        if t0 > t1 {
            core::mem::swap(&mut t0, &mut t1);
        }
        let t_err = gamma(8) * (f.length_squared() + r2) / q.abs() + gamma(4) * f.length();
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
        let len = v.length();
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
    pub fn sample_cone(&self, r: Vec3, u: Vec2) -> Option<ConeSample> {
        let dc = self.center - r;
        let dist2 = self.outside(r)?;
        let r2 = self.radius * self.radius;
        let dist = libm::sqrtf(dist2);
        let sin2 = r2 / dist2;
        let cos_max = safe_sqrt(1.0 - sin2);
        let omc = sin2 / (1.0 + cos_max);
        let local = square_to_uniform_cone_omc(u, omc);
        let frame = Frame::from_normal(dc / dist);
        let w = frame.to_world(local).normalize();
        // Distance to the near intersection along w; fall back to the tangent point on a graze.
        let cos_t = local.z;
        let b = dist * cos_t;
        let disc = r2 - dist2 * (1.0 - cos_t * cos_t).max(0.0);
        let t = b - safe_sqrt(disc);
        let (p, p_err) = self.project(r + w * t.max(0.0));
        let n = (p - self.center) / self.radius;
        Some(ConeSample {
            p,
            p_err,
            n,
            pdf: 1.0 / (2.0 * PI * omc),
        })
    }

    /// Solid-angle density of [`Sphere::sample_cone`] from `r`, or `None` when `r` is inside or
    /// on the sphere.
    pub fn cone_pdf(&self, r: Vec3) -> Option<f32> {
        let dist2 = self.outside(r)?;
        let r2 = self.radius * self.radius;
        let sin2 = r2 / dist2;
        let cos_max = safe_sqrt(1.0 - sin2);
        Some(1.0 / (2.0 * PI * (sin2 / (1.0 + cos_max))))
    }
}

//! Analytic open cylinder, as Mitsuba 3's `cylinder`: the points at distance `radius` from the
//! segment from `origin` along the unit axis `axes[2]` for `length`, without end caps. Normals
//! point away from the axis unless flipped; uv = (angle around the axis from `axes[0]` toward
//! `axes[1]` in turns, distance along the axis / length), as Mitsuba 3 defines them.
//!
//! The loader (`scene/src/shapes/cylinder.rs`) declares the parameters. The intersection is
//! solved in f64 in the cylinder's own frame, so hits stay accurate far from the origin, from
//! inside and at grazing angles; the hit point is then projected onto the surface.
use crate::math::{gamma, sqrt_f64, Aabb, Norm, Ray};
use glam::{DVec3, Vec2, Vec3};

/// A cylinder in world space (rigid frame, uniform radius).
#[derive(Clone, Copy, Debug)]
pub struct Cylinder {
    /// Centre of the base circle.
    pub origin: DVec3,
    /// Orthonormal, right-handed frame: `axes[2]` is the axis, `axes[0]` is where u = 0.
    pub axes: [DVec3; 3],
    /// Radius (> 0).
    pub radius: f64,
    /// Length along the axis (> 0).
    pub length: f64,
}

impl Cylinder {
    /// Surface area, `2 pi r l`.
    pub fn area(&self) -> f32 {
        (core::f64::consts::TAU * self.radius * self.length) as f32
    }

    /// World to local (the frame's coordinates of `p - origin`).
    #[inline]
    fn local_point(&self, p: DVec3) -> DVec3 {
        let v = p - self.origin;
        DVec3::new(
            v.dot(self.axes[0]),
            v.dot(self.axes[1]),
            v.dot(self.axes[2]),
        )
    }

    #[inline]
    fn local_vector(&self, v: DVec3) -> DVec3 {
        DVec3::new(
            v.dot(self.axes[0]),
            v.dot(self.axes[1]),
            v.dot(self.axes[2]),
        )
    }

    /// Local to world for a point.
    #[inline]
    fn world_point(&self, l: DVec3) -> DVec3 {
        self.origin + self.axes[0] * l.x + self.axes[1] * l.y + self.axes[2] * l.z
    }

    /// The nearest intersection in `(0, t_max)`: the ray parameter.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let o = self.local_point(ray.o.as_dvec3());
        let d = self.local_vector(ray.d.as_dvec3());
        let a = d.x * d.x + d.y * d.y;
        if !(a > 0.0) {
            return None;
        }
        let b = 2.0 * (d.x * o.x + d.y * o.y);
        let c = o.x * o.x + o.y * o.y - self.radius * self.radius;
        let disc = b * b - 4.0 * a * c;
        if !(disc >= 0.0) {
            return None;
        }
        // The cancellation-free pair of roots.
        let q = -0.5 * (b + libm::copysign(sqrt_f64(disc), b));
        let (mut t0, mut t1) = (q / a, if q != 0.0 { c / q } else { q / a });
        if t0 > t1 {
            core::mem::swap(&mut t0, &mut t1);
        }
        let t_max = f64::from(t_max);
        for t in [t0, t1] {
            if t > 0.0 && t < t_max {
                let z = o.z + d.z * t;
                if (0.0..=self.length).contains(&z) {
                    // The f32 distance the caller compares must stay within (0, t_max).
                    let tf = t as f32;
                    if tf > 0.0 && f64::from(tf) < t_max {
                        return Some(tf);
                    }
                }
            }
        }
        None
    }

    /// The surface point nearest to `p` (which a hit is close to), its error bound, its local
    /// coordinates `(cos, sin, z)` of the angle around the axis and the height.
    #[inline]
    pub fn project(&self, p: Vec3) -> (Vec3, Vec3, DVec3) {
        let l = self.local_point(p.as_dvec3());
        let r = sqrt_f64(l.x * l.x + l.y * l.y);
        let (c, s) = if r > 0.0 {
            (l.x / r, l.y / r)
        } else {
            (1.0, 0.0)
        };
        let z = l.z.clamp(0.0, self.length);
        let (w, err) = self.point(c, s, z);
        (w, err, DVec3::new(c, s, z))
    }

    /// The world point at angle `(cos, sin)` and height `z`, rounded to f32, with its error
    /// bound (the rounding to f32 and the f64 evaluation around it).
    #[inline]
    fn point(&self, c: f64, s: f64, z: f64) -> (Vec3, Vec3) {
        let w = self.world_point(DVec3::new(c * self.radius, s * self.radius, z));
        let p = w.as_vec3();
        let scale = (self.origin.abs() + DVec3::splat(self.radius + self.length)).as_vec3();
        (p, p.abs() * gamma(1) + scale * gamma(2))
    }

    /// Outward unit normal at local angle `(cos, sin)`.
    #[inline]
    pub fn normal(&self, c: f64, s: f64) -> Vec3 {
        (self.axes[0] * c + self.axes[1] * s)
            .as_vec3()
            .unit_or(Vec3::Z)
    }

    /// uv and dp/du at local coordinates `l = (cos, sin, z)`, as Mitsuba 3 defines them.
    #[inline]
    pub(crate) fn uv_dpdu(&self, l: DVec3) -> (Vec2, Vec3) {
        let mut phi = libm::atan2(l.y, l.x);
        if phi < 0.0 {
            phi += core::f64::consts::TAU;
        }
        let uv = Vec2::new(
            (phi / core::f64::consts::TAU) as f32,
            (l.z / self.length) as f32,
        );
        let dpdu =
            (self.axes[0] * -l.y + self.axes[1] * l.x) * (self.radius * core::f64::consts::TAU);
        (uv, dpdu.as_vec3())
    }

    /// A point uniformly distributed by area, as Mitsuba 3 places it (`u.x` along the axis,
    /// `u.y` around it): the point, its error bound, the outward normal.
    pub fn sample(&self, u: Vec2) -> (Vec3, Vec3, Vec3) {
        let phi = f64::from(u.y) * core::f64::consts::TAU;
        let (s, c) = libm::sincos(phi);
        let (p, err) = self.point(c, s, f64::from(u.x) * self.length);
        (p, err, self.normal(c, s))
    }

    /// The uv of the point [`Cylinder::sample`] places for `u` (as a ray hit there gets it).
    pub(crate) fn sample_uv(&self, u: Vec2) -> Vec2 {
        let (s, c) = libm::sincos(f64::from(u.y) * core::f64::consts::TAU);
        self.uv_dpdu(DVec3::new(c, s, f64::from(u.x) * self.length))
            .0
    }

    /// Bounding box: that of the two end circles.
    pub fn bounds(&self) -> Aabb {
        let ext = DVec3::new(
            libm::hypot(self.axes[0].x, self.axes[1].x),
            libm::hypot(self.axes[0].y, self.axes[1].y),
            libm::hypot(self.axes[0].z, self.axes[1].z),
        ) * self.radius;
        let (a, b) = (self.origin, self.origin + self.axes[2] * self.length);
        let pad = (a.abs().max(b.abs()) + ext) * 1e-6;
        Aabb {
            min: (a.min(b) - ext - pad).as_vec3(),
            max: (a.max(b) + ext + pad).as_vec3(),
        }
    }
}

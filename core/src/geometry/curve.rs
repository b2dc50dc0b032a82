//! Curves, as Mitsuba 3.9.1's `linearcurve` and `bsplinecurve` (which Embree intersects there):
//! tubes around polylines of control points `(x, y, z, radius)`, one primitive per segment.
//!
//! - Linear: a segment is the cone tangent to the spheres at its two control points plus the
//!   sphere at its end point; the first segment of each curve also has the sphere at its start.
//!   Joints and both ends of a curve are thus round (`curve_linear.rs`).
//! - B-spline: a segment is the uniform cubic B-spline of four consecutive control points, the
//!   surface the circles of radius `r(v)` perpendicular to the tangent sweep, with open ends
//!   (no caps) (`curve_bspline.rs`).
//!
//! Both report only hits from outside (a ray starting inside, or reaching the surface from the
//! inside, passes through), as Mitsuba's culled back faces. The surface parameterisation is
//! Mitsuba's: u is the angle around the tangent from a frame guided by +z, in turns; v is
//! `(segment + local parameter) / segment count`, over all curves of the file. Control points
//! are in world space (the loader applies `to_world` to positions only: radii are not scaled,
//! as in Mitsuba). The loader (`scene/src/shapes/curve.rs`) declares the parameters.
use super::curve_bspline::Cubic;
use super::curve_frame::{angle_turns, unit};
use crate::math::{Aabb, Ray};
use alloc::vec::Vec;
use glam::{DVec3, DVec4, Vec2, Vec3};

/// Which curve: how control points make segments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveBasis {
    /// Round linear segments between consecutive points.
    Linear,
    /// Uniform cubic B-spline segments over four consecutive points.
    BSpline,
}

/// A set of curves (one shape).
#[derive(Clone, Debug)]
pub struct Curve {
    /// How segments are made.
    pub basis: CurveBasis,
    /// Control points: world position and radius.
    pub points: Vec<DVec4>,
    /// Per segment: index of its first control point.
    pub segments: Vec<u32>,
    /// Per segment: whether it is the first of its curve (a linear curve's start sphere, a
    /// B-spline's open start; a segment is the last of its curve when the next is a first).
    pub first: Vec<bool>,
}

/// Mitsuba's surface quantities at a curve hit.
#[derive(Clone, Copy, Debug)]
pub struct CurveSurface {
    /// Unit outward normal.
    pub n: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Position partial along u (around the curve).
    pub dp_du: Vec3,
    /// Position partial along v (along all segments).
    pub dp_dv: Vec3,
}

impl Curve {
    /// Number of segments (primitives).
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    #[inline]
    fn point(&self, seg: usize, k: usize) -> DVec4 {
        self.points[self.segments[seg] as usize + k]
    }

    /// The cubic of B-spline segment `seg`, from its four control points.
    #[inline]
    fn cubic(&self, seg: usize) -> Cubic {
        Cubic::new([0, 1, 2, 3].map(|k| self.point(seg, k)))
    }

    /// Bounding box of segment `seg`: its control points' spheres (a B-spline segment lies in
    /// the convex hull of its control points and its radius never exceeds their largest).
    pub fn bounds(&self, seg: usize) -> Aabb {
        let n = match self.basis {
            CurveBasis::Linear => 2,
            CurveBasis::BSpline => 4,
        };
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        let mut r: f64 = 0.0;
        for k in 0..n {
            let c = self.point(seg, k);
            lo = lo.min(c.truncate());
            hi = hi.max(c.truncate());
            r = r.max(c.w.abs());
        }
        let pad = (lo.abs().max(hi.abs()) + DVec3::splat(r)) * 1e-6;
        Aabb {
            min: (lo - DVec3::splat(r) - pad).as_vec3(),
            max: (hi + DVec3::splat(r) + pad).as_vec3(),
        }
    }

    /// The nearest hit from outside on segment `seg` in `(0, t_max)`: the ray parameter and
    /// the segment's local curve parameter in `[0, 1]`.
    #[inline]
    pub fn intersect(&self, seg: usize, ray: &Ray, t_max: f32) -> Option<(f32, f32)> {
        let o = ray.o.as_dvec3();
        let d = ray.d.as_dvec3();
        let hit = match self.basis {
            CurveBasis::Linear => super::curve_linear::intersect(
                self.point(seg, 0),
                self.point(seg, 1),
                self.first[seg],
                o,
                d,
            ),
            CurveBasis::BSpline => {
                let cubic = self.cubic(seg);
                let last = seg + 1 == self.segments.len() || self.first[seg + 1];
                super::curve_bspline::intersect(&cubic, o, d, [self.first[seg], last])
            }
        }?;
        let tf = hit.0 as f32;
        (tf > 0.0 && tf < t_max).then_some((tf, hit.1 as f32))
    }

    /// The surface at point `p` of segment `seg` with local parameter `v`, as Mitsuba computes
    /// it from a hit: normal, uv and partials. Returns also the point moved onto the surface
    /// (linear) or kept (B-spline), and an error bound for it.
    pub fn surface(&self, seg: usize, v: f32, p: Vec3) -> (Vec3, Vec3, CurveSurface) {
        let v = f64::from(v.clamp(0.0, 1.0));
        let count = self.segments.len() as f64;
        let p64 = p.as_dvec3();
        let gv = ((v + seg as f64) / count) as f32;
        match self.basis {
            CurveBasis::Linear => {
                let (a, b) = (self.point(seg, 0), self.point(seg, 1));
                let c = a.truncate() * (1.0 - v) + b.truncate() * v;
                let r = a.w * (1.0 - v) + b.w * v;
                let rad = unit(p64 - c);
                let axis = unit(b.truncate() - a.truncate());
                let on = c + rad * r;
                let s = CurveSurface {
                    n: rad.as_vec3(),
                    uv: Vec2::new(angle_turns(axis, rad) as f32, gv),
                    dp_du: (axis.cross(on - c) * core::f64::consts::TAU).as_vec3(),
                    dp_dv: (((b.truncate() - a.truncate()) + rad * (b.w - a.w)) * count).as_vec3(),
                };
                let pf = on.as_vec3();
                (pf, err_bound(pf, c, r), s)
            }
            CurveBasis::BSpline => {
                let cubic = self.cubic(seg);
                let e = cubic.eval(v);
                let rad = p64 - e.c;
                let n = unit((e.dc.length_squared() - rad.dot(e.ddc)) * rad - e.dc * (e.r * e.dr));
                let radn = unit(rad);
                let t = unit(e.dc);
                let (dp_du, dp_dv) = super::curve_bspline::partials(&e, radn, count);
                let s = CurveSurface {
                    n: n.as_vec3(),
                    uv: Vec2::new(angle_turns(t, radn) as f32, gv),
                    dp_du,
                    dp_dv,
                };
                // The root finder's tolerance (see `curve_bspline.rs`) dominates rounding.
                let err = p.abs() * 1e-6 + Vec3::splat((e.r.abs() * 1e-4) as f32);
                (p, err, s)
            }
        }
    }
}

/// Error bound of a point `p` computed in f64 from centre `c` and radius `r`, then rounded.
#[inline]
fn err_bound(p: Vec3, c: DVec3, r: f64) -> Vec3 {
    p.abs() * crate::math::gamma(1)
        + (c.abs() + DVec3::splat(r.abs())).as_vec3() * crate::math::gamma(2)
}

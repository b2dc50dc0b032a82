//! One uniform cubic B-spline curve segment (see `curve.rs`): its evaluation, its ray
//! intersection and Mitsuba 3's position partials.
//!
//! Intersection. For a constant radius the tube is the envelope of the spheres `(c(v), r(v))`,
//! and the ray's first crossing of a union of spheres is the smallest of their near roots:
//! `t(v) = b(v) - sqrt(r^2 - q(v))`, with `b` the distance along the (unit) ray to the foot of
//! `c(v)` and `q` the squared distance of `c(v)` from the ray's line. So the hit is a local
//! minimum of `t(v)` over `v`:
//! 1. `t(v)` is sampled at 33 evenly spaced `v`; outside the spheres' shadow (`q > r^2`) it is
//!    continued by `b + 8 (sqrt(q) - r)`, which meets it at the shadow's edge and rises away
//!    from it, so a local minimum of the sampled values brackets each entry.
//! 2. An interval between two samples whose distances `sqrt(q) - r` might dip below zero in
//!    between (by the Lipschitz bound of the distance, the control polygon's longest leg plus
//!    its largest radius step) is searched too, so narrow grazing hits are not missed.
//! 3. Each bracket is narrowed by golden-section search to a width of 1e-10 in `v`; at a
//!    minimum `t` is flat, so its error is of the order of that width squared.
//! A minimum on the segment's end (`v` within 1e-7 of 0 or 1) is the end sphere's cap, which
//! the open tube does not have: it is no hit. With a varying radius the swept circles are not
//! the spheres' envelope; Newton steps (at most 8) on the circle conditions (`(p - c).c' = 0`,
//! `|p - c| = r`) move the point onto the circles Mitsuba (Embree) intersects. A hit counts
//! when it is in front of the origin and the ray meets the surface from outside (Mitsuba's
//! normal against the ray), as Mitsuba culls back faces.
use super::curve_frame::unit;
use crate::math::sqrt_f64;
use glam::{DVec3, DVec4, Vec3};

/// A segment's four control points (xyz, radius in w).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cubic {
    p: [DVec4; 4],
}

/// The centre line and radius at one parameter, with their derivatives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CubicEval {
    pub c: DVec3,
    pub dc: DVec3,
    pub ddc: DVec3,
    pub dddc: DVec3,
    pub r: f64,
    pub dr: f64,
}

/// Samples of `t(v)` in the first pass.
const SAMPLES: usize = 32;
/// Final bracket width of the golden-section search, in `v`.
const V_TOLERANCE: f64 = 1e-10;
/// Most Newton steps onto the circles (they stop once a step is below 1e-13).
const NEWTON_STEPS: usize = 8;
/// Slope of the continuation of `t(v)` outside the spheres' shadow.
const OUTSIDE_SLOPE: f64 = 8.0;

impl Cubic {
    /// The segment of control points `p`.
    pub(crate) fn new(p: [DVec4; 4]) -> Cubic {
        Cubic { p }
    }

    /// Centre (xyz) and radius (w) at `v`.
    #[inline]
    fn point(&self, v: f64) -> DVec4 {
        let [p0, p1, p2, p3] = self.p;
        let (v2, v3) = (v * v, v * v * v);
        let w = 1.0 - v;
        (p0 * (w * w * w)
            + p1 * (3.0 * v3 - 6.0 * v2 + 4.0)
            + p2 * (-3.0 * v3 + 3.0 * v2 + 3.0 * v + 1.0)
            + p3 * v3)
            * (1.0 / 6.0)
    }

    /// Everything at `v`.
    pub(crate) fn eval(&self, v: f64) -> CubicEval {
        let [p0, p1, p2, p3] = self.p;
        let v2 = v * v;
        let x = self.point(v);
        let d = (p0 * (-3.0 * (1.0 - v) * (1.0 - v))
            + p1 * (9.0 * v2 - 12.0 * v)
            + p2 * (-9.0 * v2 + 6.0 * v + 3.0)
            + p3 * (3.0 * v2))
            * (1.0 / 6.0);
        let dd = p0 * (1.0 - v) + p1 * (3.0 * v - 2.0) + p2 * (1.0 - 3.0 * v) + p3 * v;
        let ddd = -p0 + p1 * 3.0 - p2 * 3.0 + p3;
        CubicEval {
            c: x.truncate(),
            dc: d.truncate(),
            ddc: dd.truncate(),
            dddc: ddd.truncate(),
            r: x.w,
            dr: d.w,
        }
    }

    /// Centre of the control points.
    fn centre(&self) -> DVec3 {
        (self.p[0] + self.p[1] + self.p[2] + self.p[3]).truncate() * 0.25
    }

    /// A bound on `|c'| + |r'|` over the segment: the derivative is a quadratic B-spline of
    /// the control polygon's legs, so the longest leg bounds it.
    fn lipschitz(&self) -> f64 {
        let mut lc: f64 = 0.0;
        let mut lr: f64 = 0.0;
        for k in 0..3 {
            let e = self.p[k + 1] - self.p[k];
            lc = lc.max(e.truncate().length());
            lr = lr.max(e.w.abs());
        }
        lc + lr
    }
}

/// The sampled function at `v` for the ray from `o` along unit `d`: `(t, distance)`, `t` the
/// near root (or its continuation) and distance `sqrt(q) - r`.
#[inline]
fn near_root(cubic: &Cubic, o: DVec3, d: DVec3, v: f64) -> (f64, f64) {
    let x = cubic.point(v);
    let w = x.truncate() - o;
    let b = w.dot(d);
    let q = (w.length_squared() - b * b).max(0.0);
    let r = x.w;
    let dist = sqrt_f64(q) - r;
    if dist <= 0.0 {
        (b - sqrt_f64((r * r - q).max(0.0)), dist)
    } else {
        (b + OUTSIDE_SLOPE * dist, dist)
    }
}

/// Golden-section search for a minimum of `t(v)` in `[lo, hi]`.
fn golden(cubic: &Cubic, o: DVec3, d: DVec3, mut lo: f64, mut hi: f64) -> f64 {
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    let f = |v: f64| near_root(cubic, o, d, v).0;
    let mut x1 = hi - INV_PHI * (hi - lo);
    let mut x2 = lo + INV_PHI * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    while hi - lo > V_TOLERANCE {
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - INV_PHI * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + INV_PHI * (hi - lo);
            f2 = f(x2);
        }
    }
    // A minimum on the bracket's end is found there (within the tolerance).
    0.5 * (lo + hi)
}

/// Newton steps moving `(v, t)` onto the circle perpendicular to the tangent (Mitsuba's
/// surface when the radius varies). Returns the input when a step fails.
fn onto_circles(cubic: &Cubic, o: DVec3, d: DVec3, v: f64, t: f64) -> (f64, f64) {
    let (mut v, mut t) = (v, t);
    for _ in 0..NEWTON_STEPS {
        let e = cubic.eval(v);
        let rad = o + d * t - e.c;
        let f1 = rad.dot(e.dc);
        let f2 = rad.length_squared() - e.r * e.r;
        // Jacobian of (f1, f2) in (v, t).
        let a11 = -e.dc.length_squared() + rad.dot(e.ddc);
        let a12 = d.dot(e.dc);
        let a21 = -2.0 * rad.dot(e.dc) - 2.0 * e.r * e.dr;
        let a22 = 2.0 * rad.dot(d);
        let det = a11 * a22 - a12 * a21;
        if !(det.abs() > 1e-300) {
            return (v, t);
        }
        let dv = (f1 * a22 - f2 * a12) / det;
        let dt = (a11 * f2 - a21 * f1) / det;
        if !(dv.is_finite() && dt.is_finite()) {
            return (v, t);
        }
        v -= dv;
        t -= dt;
        if dv.abs() < 1e-13 && dt.abs() < 1e-13 * t.abs().max(1.0) {
            break;
        }
    }
    (v, t)
}

/// The nearest hit from outside of the ray `o + t d` with the segment: `(t, v)`.
pub(crate) fn intersect(cubic: &Cubic, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
    let len = d.length();
    if !(len > 0.0) {
        return None;
    }
    let dn = d / len;
    // Move the origin next to the segment (t is measured from here, then shifted back).
    let shift = (cubic.centre() - o).dot(dn);
    let org = o + dn * shift;
    let step = 1.0 / SAMPLES as f64;
    let mut ts = [0.0; SAMPLES + 1];
    let mut ds = [0.0; SAMPLES + 1];
    for k in 0..=SAMPLES {
        (ts[k], ds[k]) = near_root(cubic, org, dn, k as f64 * step);
    }
    let lip = cubic.lipschitz();
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |lo: f64, hi: f64| {
        let v = golden(cubic, org, dn, lo.max(0.0), hi.min(1.0));
        if !(1e-7..=1.0 - 1e-7).contains(&v) {
            return; // the end cap of the open tube
        }
        let (t, dist) = near_root(cubic, org, dn, v);
        if dist > 0.0 {
            return;
        }
        let (v, t) = onto_circles(cubic, org, dn, v, t);
        if !(0.0..=1.0).contains(&v) {
            return;
        }
        let e = cubic.eval(v);
        let rad = org + dn * t - e.c;
        let n = (e.dc.length_squared() - rad.dot(e.ddc)) * rad - e.dc * (e.r * e.dr);
        let t_world = (t + shift) / len;
        if n.dot(dn) < 0.0 && t_world > 0.0 && best.is_none_or(|(bt, _)| t_world < bt) {
            best = Some((t_world, v));
        }
    };
    // Whether the distance may dip to zero between samples `k` and `k + 1`.
    let dip = |k: usize| k < SAMPLES && 0.5 * (ds[k] + ds[k + 1] - lip * step) <= 0.0;
    for k in 0..=SAMPLES {
        let left = if k > 0 { ts[k - 1] } else { f64::INFINITY };
        let right = if k < SAMPLES {
            ts[k + 1]
        } else {
            f64::INFINITY
        };
        let near = ds[k] <= 0.0 || dip(k) || (k > 0 && dip(k - 1));
        if ts[k] <= left && ts[k] <= right && near {
            consider((k as f64 - 1.0) * step, (k as f64 + 1.0) * step);
        }
    }
    for k in 0..SAMPLES {
        if ds[k] > 0.0 && ds[k + 1] > 0.0 && dip(k) {
            consider(k as f64 * step, (k as f64 + 1.0) * step);
        }
    }
    best
}

/// Mitsuba 3's position partials at a hit with unit radial direction `rad`, over a curve of
/// `count` segments: `dp/du` is `2 pi r` around the tangent, `dp/dv` follows the centre line,
/// the radius and the Frenet frame's turn along the global parameter.
pub(crate) fn partials(e: &CubicEval, rad: DVec3, count: f64) -> (Vec3, Vec3) {
    let nc = e.dc.length();
    let cr = e.dc.cross(e.ddc);
    let ncr = cr.length();
    let t = e.dc / nc;
    let mut kappa = ncr / (nc * nc * nc);
    let mut tau = e.dddc.dot(cr) / (ncr * ncr);
    if ncr < 1e-6 || e.dddc.length() < 1e-6 {
        tau = 0.0;
    }
    let mut fn_ = unit(cr.cross(e.dc));
    let mut fb = unit(t.cross(fn_));
    if !(kappa >= f64::from(f32::EPSILON) * 0.5) {
        kappa = 0.0;
        tau = 0.0;
        let (s, tt) = duff_frame(t);
        fn_ = s;
        fb = tt;
    }
    let (cos, sin) = (fn_.dot(rad), fb.dot(rad));
    let radu = -fn_ * sin + fb * cos;
    let radv = (-t * kappa + fb * tau) * (nc * cos) - fn_ * (nc * sin * tau);
    let dp_du = radu * (e.r * core::f64::consts::TAU);
    let dp_dv = (e.dc + rad * e.dr + radv * e.r) * count;
    (dp_du.as_vec3(), dp_dv.as_vec3())
}

/// The frame Mitsuba 3 puts around a unit direction (Duff et al.'s): `(s, t)`.
fn duff_frame(n: DVec3) -> (DVec3, DVec3) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

//! One uniform cubic B-spline curve segment (see `curve.rs`): its evaluation, its ray
//! intersection and Mitsuba 3's position partials.
//!
//! Intersection. For a constant radius the tube is the envelope of the spheres `(c(v), r(v))`,
//! and the ray's first crossing of a union of spheres is the smallest of their near roots:
//! `t(v) = b(v) - sqrt(r^2 - q(v))`, with `b` the distance along the (unit) ray to the foot of
//! `c(v)` and `q` the squared distance of `c(v)` from the ray's line. So the hit is a local
//! minimum of `t(v)` over `v`:
//! 1. `t(v)` and the distance `sqrt(q) - r` are sampled at 33 evenly spaced `v`. The ray meets
//!    the spheres over runs of samples at distance <= 0, the shadow; its edges are found by
//!    bisection. At an edge `t` falls steeply into the shadow, so each local minimum of `t`
//!    over a run's edges and samples brackets a minimum inside.
//! 2. An interval between two samples outside whose distance might dip below zero in between
//!    (by the Lipschitz bound of the distance, the control polygon's longest leg plus its
//!    largest radius step) is searched for its least distance, so narrow grazing shadows are
//!    not missed.
//! 3. Each bracket is narrowed by golden-section search to a width of 1e-10 in `v`; at a
//!    minimum `t` is flat, so its error is of the order of that width squared.
//!
//! A minimum on the segment's end (`v` within 1e-7 of 0 or 1) is, at the curve's end, the end
//! sphere's cap, which the open tube does not have: no hit; at a joint it is a hit when `t`
//! rises on both sides of it (1e-4 before it and 1e-4 beyond it on the segment's own cubic,
//! which the next segment continues to second order). With a varying radius the swept circles are not
//! the spheres' envelope; Newton steps (at most 8) on the circle conditions (`(p - c).c' = 0`,
//! `|p - c| = r`) move the point onto the circles Mitsuba (Embree) intersects. A hit counts
//! when it is in front of the origin and the ray meets the surface from outside (Mitsuba's
//! normal against the ray), as Mitsuba culls back faces.
use super::curve_frame::unit;
use crate::math::{sqrt_f64, Norm};
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
/// Most Newton steps onto the circles (they stop once a step is below 1e-13; a hit whose
/// steps do not get there is dropped).
const NEWTON_STEPS: usize = 8;
/// How far past a joint the cubic is followed to see that `t` rises there.
const JOINT_STEP: f64 = 1e-4;

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
            lc = lc.max(e.truncate().norm());
            lr = lr.max(e.w.abs());
        }
        lc + lr
    }
}

/// The near root at `v` for the ray from `o` along unit `d`, and the distance `sqrt(q) - r` of
/// the sphere from the ray's line (the root is that of the grazing ray, `b`, where the sphere is
/// missed).
#[inline]
fn near_root(cubic: &Cubic, o: DVec3, d: DVec3, v: f64) -> (f64, f64) {
    let x = cubic.point(v);
    let w = x.truncate() - o;
    let b = w.dot(d);
    let q = (w.length_squared() - b * b).max(0.0);
    let r = x.w;
    (b - sqrt_f64((r * r - q).max(0.0)), sqrt_f64(q) - r)
}

/// Golden-section search for a minimum of `f` in `[lo, hi]`, to a width of [`V_TOLERANCE`].
fn golden(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
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

/// The edge of the spheres' shadow between `inside` (distance <= 0) and `outside`, by
/// bisection to [`V_TOLERANCE`]; the end returned is on the inside.
fn edge(cubic: &Cubic, o: DVec3, d: DVec3, mut inside: f64, mut outside: f64) -> f64 {
    while (outside - inside).abs() > V_TOLERANCE {
        let mid = 0.5 * (inside + outside);
        if near_root(cubic, o, d, mid).1 <= 0.0 {
            inside = mid;
        } else {
            outside = mid;
        }
    }
    inside
}

/// Newton steps moving `(v, t)` onto the circle perpendicular to the tangent (Mitsuba's
/// surface when the radius varies); `None` unless they converge (a step below 1e-13).
fn onto_circles(cubic: &Cubic, o: DVec3, d: DVec3, v: f64, t: f64) -> Option<(f64, f64)> {
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
        let dv = (f1 * a22 - f2 * a12) / det;
        let dt = (a11 * f2 - a21 * f1) / det;
        if !(dv.is_finite() && dt.is_finite()) {
            return None;
        }
        v -= dv;
        t -= dt;
        if dv.abs() < 1e-13 && dt.abs() < 1e-13 * t.abs().max(1.0) {
            return Some((v, t));
        }
    }
    None
}

/// The nearest hit from outside of the ray `o + t d` with the segment: `(t, v)`. `open`:
/// whether the segment's start and end are its curve's ends (open), else joints with the
/// neighbouring segments.
pub(crate) fn intersect(cubic: &Cubic, o: DVec3, d: DVec3, open: [bool; 2]) -> Option<(f64, f64)> {
    let len = d.norm();
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
    let root = |v: f64| near_root(cubic, org, dn, v).0;
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |lo: f64, hi: f64| {
        let v = golden(root, lo.max(0.0), hi.min(1.0));
        let (t, dist) = near_root(cubic, org, dn, v);
        // A minimum on an end: the open tube's missing cap, or at a joint a minimum of the
        // whole curve if `t` rises beyond it too (the neighbour continues this cubic to second
        // order, so the cubic itself is followed a little past the joint).
        for (end, within, beyond, is_open) in [
            (v < 1e-7, JOINT_STEP, -JOINT_STEP, open[0]),
            (v > 1.0 - 1e-7, 1.0 - JOINT_STEP, 1.0 + JOINT_STEP, open[1]),
        ] {
            if end && (is_open || root(beyond) < t || root(within) < t) {
                return;
            }
        }
        if dist > 0.0 {
            return;
        }
        let Some((v, t)) = onto_circles(cubic, org, dn, v, t) else {
            return;
        };
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
    let at = |k: usize| k as f64 * step;
    let mut k = 0;
    while k <= SAMPLES {
        if ds[k] > 0.0 {
            // A shadow too narrow to hold a sample, where the distance may dip below zero.
            if k < SAMPLES && ds[k + 1] > 0.0 && 0.5 * (ds[k] + ds[k + 1] - lip * step) <= 0.0 {
                let vm = golden(|v| near_root(cubic, org, dn, v).1, at(k), at(k + 1));
                if near_root(cubic, org, dn, vm).1 <= 0.0 {
                    let lo = edge(cubic, org, dn, vm, at(k));
                    let hi = edge(cubic, org, dn, vm, at(k + 1));
                    consider(lo, hi);
                }
            }
            k += 1;
            continue;
        }
        // A run of samples k..=j in the shadow, between its edges: each local minimum of `t`
        // over the edges and samples brackets one.
        let mut j = k;
        while j < SAMPLES && ds[j + 1] <= 0.0 {
            j += 1;
        }
        let lo = if k == 0 {
            0.0
        } else {
            edge(cubic, org, dn, at(k), at(k - 1))
        };
        let hi = if j == SAMPLES {
            1.0
        } else {
            edge(cubic, org, dn, at(j), at(j + 1))
        };
        let n = j - k + 3;
        let point = |i: usize| match i {
            0 => lo,
            i if i == n - 1 => hi,
            i => at(k + i - 1),
        };
        let value = |i: usize| match i {
            0 => root(lo),
            i if i == n - 1 => root(hi),
            i => ts[k + i - 1],
        };
        for i in 0..n {
            let here = value(i);
            let left_ok = i == 0 || here <= value(i - 1);
            let right_ok = i == n - 1 || here <= value(i + 1);
            if left_ok && right_ok {
                consider(point(i.saturating_sub(1)), point((i + 1).min(n - 1)));
            }
        }
        k = j + 1;
    }
    best
}

/// Mitsuba 3's position partials at a hit with unit radial direction `rad`, over a curve of
/// `count` segments: `dp/du` is `2 pi r` around the tangent, `dp/dv` follows the centre line,
/// the radius and the Frenet frame's turn along the global parameter.
pub(crate) fn partials(e: &CubicEval, rad: DVec3, count: f64) -> (Vec3, Vec3) {
    let nc = e.dc.norm();
    let cr = e.dc.cross(e.ddc);
    let ncr = cr.norm();
    let t = e.dc / nc;
    let mut kappa = ncr / (nc * nc * nc);
    let mut tau = e.dddc.dot(cr) / (ncr * ncr);
    if ncr < 1e-6 || e.dddc.norm() < 1e-6 {
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

//! Ray intersection of one round linear curve segment (see `curve.rs`): the cone tangent to
//! the spheres `(p0, r0)` and `(p1, r1)`, between its two tangent circles, plus the end sphere,
//! plus the start sphere on a curve's first segment. The segment's solid is then the convex
//! hull of its spheres (open at the start on later segments, whose start sphere is the
//! previous segment's end), so the first boundary crossing along the ray is where it enters.
//! Solved in f64 with the origin moved next to the segment; each quadric's roots are
//! cancellation-free.
//!
//! The local curve parameter of a cone point `h` is the parameter of the sphere the cone
//! touches there, `((h - p0).(p1 - p0) + r0 (r1 - r0)) / (|p1 - p0|^2 - (r1 - r0)^2)`, so that
//! `h - c(v)` is the normal (`c` the centre line); it is 1 on the end sphere and 0 on the start
//! sphere, as Mitsuba receives it from Embree.
use crate::math::sqrt_f64;
use glam::{DVec3, DVec4};

/// The roots of `a t^2 + b t + c = 0`, smaller first (none when complex; one when `a` is 0).
#[inline]
fn roots(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        if b == 0.0 {
            return None;
        }
        let t = -c / b;
        return Some((t, t));
    }
    let disc = b * b - 4.0 * a * c;
    if !(disc >= 0.0) {
        return None;
    }
    let q = -0.5 * (b + libm::copysign(sqrt_f64(disc), b));
    let (t0, t1) = if q != 0.0 { (q / a, c / q) } else { (0.0, 0.0) };
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// The first crossing of the ray `o + t d` with the segment from `a` to `b` (xyz, radius in w)
/// when the ray enters there from outside: `(t, local parameter)`. `first`: the segment begins
/// its curve and has its start sphere.
pub(crate) fn intersect(a: DVec4, b: DVec4, first: bool, o: DVec3, d: DVec3) -> Option<(f64, f64)> {
    let (p0, r0, p1, r1) = (a.truncate(), a.w, b.truncate(), b.w);
    let dd = d.length_squared();
    if !(dd > 0.0) {
        return None;
    }
    // Move the origin next to the segment: the quadrics' coefficients stay small.
    let shift = (0.5 * (p0 + p1) - o).dot(d) / dd;
    let org = o + d * shift;
    let dp = p1 - p0;
    let dr = r1 - r0;
    let dpdp = dp.length_squared();
    let g = dpdp - dr * dr;
    let o0 = org - p0;
    let od = o0.dot(d);
    let odp = o0.dot(dp);
    let ddp = d.dot(dp);
    // y(t): the projection along the axis, scaled by |dp|, shifted so the cone spans [0, g].
    let y = |t: f64| odp + t * ddp + r0 * dr;

    let mut best: Option<(f64, f64, DVec3)> = None;
    let mut take = |t: f64, v: f64, n: DVec3| {
        if best.is_none_or(|(bt, _, _)| t < bt) {
            best = Some((t, v, n));
        }
    };
    if g > 0.0 {
        let qa = g * dd - ddp * ddp;
        let qb = 2.0 * (g * od - ddp * (odp + r0 * dr));
        let qc = g * o0.length_squared() - odp * odp - r0 * r0 * dpdp - 2.0 * r0 * dr * odp;
        if let Some((t0, t1)) = roots(qa, qb, qc) {
            for t in [t0, t1] {
                let yt = y(t);
                if (0.0..=g).contains(&yt) {
                    let v = yt / g;
                    let c = p0 + dp * v;
                    take(t, v, org + d * t - c);
                }
            }
        }
    }
    let mut sphere = |centre: DVec3, r: f64, v: f64, keep: &dyn Fn(f64) -> bool| {
        let oc = org - centre;
        if let Some((t0, t1)) = roots(dd, 2.0 * oc.dot(d), oc.length_squared() - r * r) {
            for t in [t0, t1] {
                if g <= 0.0 || keep(y(t)) {
                    take(t, v, oc + d * t);
                }
            }
        }
    };
    sphere(p1, r1, 1.0, &|yt| yt > g);
    if first {
        sphere(p0, r0, 0.0, &|yt| yt < 0.0);
    }
    let (t, v, n) = best?;
    // Entered from outside, in front of the origin: not the far side of an open start.
    (n.dot(d) < 0.0 && t + shift > 0.0).then_some((t + shift, v))
}

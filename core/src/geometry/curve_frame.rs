//! The frame Mitsuba 3 puts around a curve's tangent, from which a curve's u (the angle around
//! it) is measured: the +z direction made perpendicular to the tangent (+y where the tangent is
//! along z) and its cross product with the tangent.
use crate::math::sqrt_f64;
use glam::DVec3;

/// `v / |v|`, or +z for a zero vector.
#[inline]
pub(crate) fn unit(v: DVec3) -> DVec3 {
    let l = sqrt_f64(v.length_squared());
    if l > 0.0 {
        v / l
    } else {
        DVec3::Z
    }
}

/// Mitsuba's frame around a unit tangent `t`: `(rot, rad)`, `rot` the +z direction made
/// perpendicular to `t` (+y where `t` is along z), `rad = rot x t`.
#[inline]
pub(crate) fn local_frame(t: DVec3) -> (DVec3, DVec3) {
    let guide = DVec3::Z;
    let rot = if t.dot(guide).abs() == 1.0 {
        DVec3::Y
    } else {
        unit(guide - t * t.dot(guide))
    };
    (rot, rot.cross(t))
}

/// The angle of unit radial direction `rad` around unit tangent `t`, in turns in `[0, 1)`.
#[inline]
pub(crate) fn angle_turns(t: DVec3, rad: DVec3) -> f64 {
    let (rot, rd) = local_frame(t);
    let mut a = libm::atan2(rot.dot(rad), rd.dot(rad));
    if a < 0.0 {
        a += core::f64::consts::TAU;
    }
    let u = a / core::f64::consts::TAU;
    if u >= 1.0 {
        0.0
    } else {
        u
    }
}

//! The "cap square": chi-square coordinates for direction samplers confined to a cone.
//!
//! A direction maps to the unit square by `x = (1 - cos θ) / omc_box`, `y = φ / 2π`, with `θ`,
//! `φ` measured in `frame` (axis `frame[2]`). Since `dω = d(cos θ) dφ`, a solid-angle density
//! `p(ω)` becomes the area density `p(ω) · 2π · omc_box` on the square: this bins only the cap
//! `1 - cos θ <= omc_box` around the axis, at any angular size, with cells of equal solid angle.
use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::TAU;
use tessera_core::math::Norm;

/// An orthonormal frame `[s, t, a]` (f64) with `a` the given unit axis; built here, not with the
/// core's `Frame`, so that the tests do not share the sampler's choice of tangents.
pub fn frame_around(a: DVec3) -> [DVec3; 3] {
    let helper = if a.x.abs() < 0.6 { DVec3::X } else { DVec3::Y };
    let s = helper.cross(a).unit();
    let t = a.cross(s);
    [s, t, a]
}

/// The square point of direction `d`; `1 - cos θ` is computed as `(x² + y²) / (|d| (|d| + z))`,
/// without cancellation.
pub fn cap_coords(d: Vec3, frame: &[DVec3; 3], omc_box: f64) -> Vec2 {
    let d = d.as_dvec3();
    let (x, y, z) = (d.dot(frame[0]), d.dot(frame[1]), d.dot(frame[2]));
    let len = (x * x + y * y + z * z).sqrt();
    let omc = (x * x + y * y) / (len * (len + z));
    let mut phi = y.atan2(x);
    if phi < 0.0 {
        phi += TAU;
    }
    Vec2::new((omc / omc_box) as f32, (phi / TAU) as f32)
}

/// Inverse of [`cap_coords`]: the unit direction (f64) of a point of the square.
pub fn cap_dir(p: Vec2, frame: &[DVec3; 3], omc_box: f64) -> DVec3 {
    let omc = f64::from(p.x) * omc_box;
    let cos = 1.0 - omc;
    let sin = (omc * (2.0 - omc)).max(0.0).sqrt();
    let phi = TAU * f64::from(p.y);
    frame[0] * (sin * phi.cos()) + frame[1] * (sin * phi.sin()) + frame[2] * cos
}

//! Warping functions: uniform points in `[0,1)^2` to directions and positions, with their pdfs.
//! Every pair here has a chi-square test in `tests/`.
use crate::math::{safe_sqrt, sincos_turns, INV_FOUR_PI, INV_PI, PI};
use glam::{Vec2, Vec3};

/// Uniform direction on the unit sphere.
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = safe_sqrt(1.0 - z * z);
    let (s, c) = sincos_turns(u.y);
    Vec3::new(r * c, r * s, z)
}

/// Density of [`square_to_uniform_sphere`] (solid angle).
pub fn uniform_sphere_pdf() -> f32 {
    INV_FOUR_PI
}

/// Concentric (Shirley-Chiu) map of the square onto the unit disk: uniform by area.
pub fn square_to_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    // theta = q in the x-dominant wedges and pi/2 - q in the y-dominant ones, with |q| <= pi/4;
    // cos and sin of pi/2 - q are sin and cos of q, so one sincos of the small angle serves
    // both, with no range reduction inside sincosf (whose range branches mispredicted).
    let x_major = o.x.abs() > o.y.abs();
    let (r, num) = if x_major { (o.x, o.y) } else { (o.y, o.x) };
    let q = (PI / 4.0) * (num / r);
    let (s, c) = libm::sincosf(q);
    if x_major {
        Vec2::new(r * c, r * s)
    } else {
        Vec2::new(r * s, r * c)
    }
}

/// Density of [`square_to_uniform_disk_concentric`] (area, unit disk).
pub fn uniform_disk_pdf(p: Vec2) -> f32 {
    if p.length_squared() <= 1.0 {
        INV_PI
    } else {
        0.0
    }
}

/// Cosine-weighted direction on the +z hemisphere (Malley's method).
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = square_to_uniform_disk_concentric(u);
    let z = safe_sqrt(1.0 - d.length_squared());
    Vec3::new(d.x, d.y, z)
}

/// Density of [`square_to_cosine_hemisphere`]: `cos(theta) / pi` on the upper hemisphere.
pub fn cosine_hemisphere_pdf(v: Vec3) -> f32 {
    if v.z > 0.0 {
        v.z * INV_PI
    } else {
        0.0
    }
}

/// Uniform direction in the cone around +z with `cos(theta) >= cos_max`.
pub fn square_to_uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    square_to_uniform_cone_omc(u, 1.0 - cos_max)
}

/// [`square_to_uniform_cone`] parametrized by `1 - cos_max`, which stays accurate for the tiny
/// cones of far-away spheres (where `cos_max` rounds to 1).
pub fn square_to_uniform_cone_omc(u: Vec2, one_minus_cos_max: f32) -> Vec3 {
    let omc = u.x * one_minus_cos_max; // 1 - cos(theta)
    let cos_t = 1.0 - omc;
    let sin_t = safe_sqrt(omc * (2.0 - omc));
    let (s, c) = sincos_turns(u.y);
    Vec3::new(sin_t * c, sin_t * s, cos_t)
}

/// Density of [`square_to_uniform_cone`].
pub fn uniform_cone_pdf(v: Vec3, cos_max: f32) -> f32 {
    if v.z >= cos_max {
        1.0 / (2.0 * PI * (1.0 - cos_max))
    } else {
        0.0
    }
}

/// Uniform barycentrics `(b1, b2)` on a triangle (`b0 = 1 - b1 - b2`), by the square-root map.
pub fn square_to_uniform_triangle(u: Vec2) -> Vec2 {
    let t = safe_sqrt(u.x);
    Vec2::new(1.0 - t, u.y * t)
}

/// Density of [`square_to_uniform_triangle`] in the `(b1, b2)` plane: 2 inside, 0 outside.
pub fn uniform_triangle_pdf(b: Vec2) -> f32 {
    if b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 {
        2.0
    } else {
        0.0
    }
}

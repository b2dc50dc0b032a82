//! What light selection at a vertex knows of each light: a cheap estimate of how strongly it
//! lights a point, and the direction it lights it from.
//!
//! The estimate is the irradiance the light would give a surface at the point facing it:
//! radiance times the solid angle it subtends (exact for a sphere; area times the cosine at the
//! light over the squared distance for a flat light, a quarter of the area for any other shape,
//! both capped at a hemisphere), intensity over the squared distance for point, spot and
//! projector lights (on the axis, for a texture's mean), irradiance for directional lights,
//! radiance times pi for environments. It only steers a choice whose probabilities are exact,
//! so a poor estimate costs variance, never bias.
use crate::emitter::{luminance, Emitter, EmitterCtx};
use crate::geometry::ShapeKind;
use crate::math::{sqrt, Norm, PI};
use glam::Vec3;

/// A light as light selection sees it.
#[derive(Clone, Copy, Debug)]
pub enum LightBound {
    /// A spherical area light: the cone it subtends.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius.
        radius: f32,
        /// Luminance of its radiance.
        lum: f32,
    },
    /// A flat one-sided area light (a planar mesh, a rectangle, a disk).
    Flat {
        /// Area-weighted centre.
        center: Vec3,
        /// Unit normal of the lit side.
        normal: Vec3,
        /// Area.
        area: f32,
        /// Luminance of its radiance.
        lum: f32,
    },
    /// Any other area light, seen as a quarter of its area from every side.
    Solid {
        /// Area-weighted centre.
        center: Vec3,
        /// Area.
        area: f32,
        /// Luminance of its radiance.
        lum: f32,
    },
    /// A point or spot light.
    Point {
        /// Position.
        position: Vec3,
        /// Luminance of its (largest) intensity.
        lum: f32,
    },
    /// A directional light or a distant disk: light from one direction.
    Direction {
        /// Unit direction toward the light.
        to_light: Vec3,
        /// Luminance of the irradiance it gives a surface facing it.
        lum: f32,
    },
    /// An environment: light from everywhere.
    Environment {
        /// Luminance of the irradiance a uniform environment gives whose radiance is the mean of
        /// the luminance its sampling tables sample.
        lum: f32,
    },
}

/// What a light gives a point, as [`LightBound::estimate`] sees it.
#[derive(Clone, Copy, Debug)]
pub struct LightEstimate {
    /// Estimated irradiance (luminance) on a surface facing the light; zero where it cannot
    /// reach.
    pub irradiance: f32,
    /// Unit direction toward the light (`None` for an environment).
    pub toward: Option<Vec3>,
}

impl LightBound {
    /// The bound of `e`.
    pub fn of(e: &Emitter, ctx: &EmitterCtx) -> LightBound {
        match e {
            Emitter::Area(a) => {
                let lum = luminance(a.radiance).max(0.0);
                let shape = &ctx.shapes[a.shape as usize];
                let flip = if shape.flip_normals { -1.0 } else { 1.0 };
                match &shape.kind {
                    ShapeKind::Sphere(s) => LightBound::Sphere {
                        center: s.center,
                        radius: s.radius,
                        lum,
                    },
                    ShapeKind::Cylinder(c) => LightBound::Solid {
                        center: (c.origin + c.axes[2] * (0.5 * c.length)).as_vec3(),
                        area: c.area(),
                        lum,
                    },
                    // The loader refuses an emitter on a curve; nothing to bound.
                    ShapeKind::Curve(_) => LightBound::Solid {
                        center: Vec3::ZERO,
                        area: 0.0,
                        lum: 0.0,
                    },
                    ShapeKind::Disk(i) => {
                        let d = &ctx.disks[*i as usize];
                        LightBound::Flat {
                            center: d.to_world.point(Vec3::ZERO),
                            normal: d.normal * flip,
                            area: d.area,
                            lum,
                        }
                    }
                    ShapeKind::Mesh(m) => {
                        let mut center = Vec3::ZERO;
                        let mut normal = Vec3::ZERO;
                        let mut area = 0.0;
                        for i in 0..m.indices.len() {
                            let a = m.triangle_area(i);
                            let [p0, p1, p2] = m.vertices(i);
                            center += (p0 + p1 + p2) * (a / 3.0);
                            normal += m.face_normal(i) * a;
                            area += a;
                        }
                        if !(area > 0.0) {
                            return LightBound::Point {
                                position: Vec3::ZERO,
                                lum: 0.0,
                            };
                        }
                        center /= area;
                        // Flat when the area-weighted normal is as long as the area: every
                        // face points the same way.
                        let len = normal.norm();
                        if len >= area * 0.9999 {
                            LightBound::Flat {
                                center,
                                normal: normal / len * flip,
                                area,
                                lum,
                            }
                        } else {
                            LightBound::Solid { center, area, lum }
                        }
                    }
                }
            }
            Emitter::Point(p) => LightBound::Point {
                position: p.position,
                lum: luminance(p.intensity).max(0.0),
            },
            Emitter::Spot(s) => LightBound::Point {
                position: s.position,
                lum: s.luminance().max(0.0),
            },
            Emitter::Projector(p) => LightBound::Point {
                position: p.position,
                lum: p.axis_luminance().max(0.0),
            },
            Emitter::Directional(d) => LightBound::Direction {
                to_light: -d.direction,
                lum: luminance(d.irradiance).max(0.0),
            },
            Emitter::DistantDisk(d) => LightBound::Direction {
                to_light: d.to_world * Vec3::Z,
                lum: luminance(d.radiance).max(0.0) * d.solid_angle(),
            },
            Emitter::Constant(c) => LightBound::Environment {
                lum: PI * luminance(c.radiance).max(0.0),
            },
            Emitter::EnvMap(e) => LightBound::Environment {
                // The part of its light its tables sample (all of it, or with MIS-compensated
                // tables what lies above the mean, BSDF sampling finding the rest), spread
                // evenly over the sphere: that integral over 4 pi, times pi.
                lum: PI * e.sampled_luminance_integral().max(0.0) / (4.0 * PI),
            },
        }
    }

    /// What the light gives the point `p`.
    #[inline]
    pub fn estimate(&self, p: Vec3) -> LightEstimate {
        match *self {
            LightBound::Sphere {
                center,
                radius,
                lum,
            } => {
                let r2 = radius * radius;
                from_point(p, center, r2, lum, |_, dist2| {
                    // 2 pi (1 - cos theta_max), without cancellation for small spheres.
                    let sin2 = r2 / dist2;
                    lum * (2.0 * PI * sin2 / (1.0 + sqrt(1.0 - sin2)))
                })
            }
            LightBound::Flat {
                center,
                normal,
                area,
                lum,
            } => from_point(p, center, 0.0, lum, |w, dist2| {
                lum * (area * (-normal.dot(w)).max(0.0) / dist2).min(2.0 * PI)
            }),
            LightBound::Solid { center, area, lum } => {
                from_point(p, center, 0.0, lum, |_, dist2| {
                    lum * (0.25 * area / dist2).min(2.0 * PI)
                })
            }
            // A point light at the point itself lights nothing measurable.
            LightBound::Point { position, lum } => {
                from_point(p, position, 0.0, 0.0, |_, dist2| lum / dist2)
            }
            LightBound::Direction { to_light, lum } => LightEstimate {
                irradiance: lum,
                toward: Some(to_light),
            },
            LightBound::Environment { lum } => LightEstimate {
                irradiance: lum,
                toward: None,
            },
        }
    }
}

/// What a light at `at` gives `p`: `irradiance(unit direction, squared distance)`, or, when the
/// squared distance is not above `inside2` (on or inside the light), half the sky's worth of
/// radiance `lum` from no particular direction.
#[inline]
fn from_point(
    p: Vec3,
    at: Vec3,
    inside2: f32,
    lum: f32,
    irradiance: impl Fn(Vec3, f32) -> f32,
) -> LightEstimate {
    let d = at - p;
    let dist2 = d.length_squared();
    if !(dist2 > inside2) {
        return LightEstimate {
            irradiance: 2.0 * PI * lum,
            toward: None,
        };
    }
    // One division, not one per component: the estimate only steers.
    let w = d * (1.0 / sqrt(dist2));
    LightEstimate {
        irradiance: irradiance(w, dist2),
        toward: Some(w),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere's estimate is its radiance times the exact solid angle of its cone,
    /// 2 pi (1 - cos theta_max), also for a sphere so small that 1 - cos would cancel.
    #[test]
    fn sphere_is_radiance_times_cone_solid_angle() {
        for (radius, dist) in [(1.0f32, 2.0f32), (0.5, 10.0), (1e-4, 100.0)] {
            let b = LightBound::Sphere {
                center: Vec3::new(0.0, dist, 0.0),
                radius,
                lum: 3.0,
            };
            let e = b.estimate(Vec3::ZERO);
            let sin2 = (radius as f64 / dist as f64).powi(2);
            let omega = 2.0 * core::f64::consts::PI * sin2 / (1.0 + (1.0 - sin2).sqrt());
            let rel = (e.irradiance as f64 / (3.0 * omega) - 1.0).abs();
            assert!(
                rel < 1e-5,
                "r {radius} d {dist}: {} vs {}",
                e.irradiance,
                3.0 * omega
            );
            assert_eq!(e.toward, Some(Vec3::Y));
        }
        let inside = LightBound::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
            lum: 1.0,
        };
        assert_eq!(inside.estimate(Vec3::X * 0.5).toward, None);
    }

    /// A flat light lights only its front side, by area times the cosine at the light over the
    /// squared distance, capped at a hemisphere.
    #[test]
    fn flat_light_is_one_sided_and_capped() {
        let b = LightBound::Flat {
            center: Vec3::ZERO,
            normal: -Vec3::Y,
            area: 0.5,
            lum: 2.0,
        };
        let below = b.estimate(Vec3::new(0.0, -2.0, 0.0));
        assert!((below.irradiance - 2.0 * 0.5 / 4.0).abs() < 1e-6);
        let oblique = b.estimate(Vec3::new(2.0, -2.0, 0.0));
        let cos = core::f32::consts::FRAC_1_SQRT_2;
        assert!((oblique.irradiance - 2.0 * 0.5 * cos / 8.0).abs() < 1e-6);
        assert_eq!(b.estimate(Vec3::new(0.0, 2.0, 0.0)).irradiance, 0.0);
        let close = b.estimate(Vec3::new(0.0, -1e-3, 0.0));
        assert_eq!(close.irradiance, 2.0 * 2.0 * PI);
    }
}

//! Nori's `simple` integrator: one point light that the scene file gives to the integrator
//! itself (`position`, `energy`), seen by every surface as a perfectly diffuse reflector of
//! albedo 1:
//!
//! `L = energy / (4 pi^2) * max(0, cos theta) / |p - x|^2 * V(x, p)`,
//!
//! with `theta` between the shading normal at `x` and the direction to the light `p`. No other
//! light counts (emitters, BSDFs and their colours are not looked at), and nothing is random
//! but the pixel position.
use super::probe::{PathEnd, Probe, RayKind};
use crate::math::{Norm, Ray};
use crate::scene::Scene;
use crate::Color;
use core::f32::consts::PI;
use glam::Vec3;

/// Diffuse shading by one point light with shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimpleIntegrator {
    /// The light's position (world space).
    pub position: Vec3,
    /// Its power (flux), per channel.
    pub energy: Color,
}

impl SimpleIntegrator {
    /// Radiance toward the camera from the first surface `ray` meets (black where it meets
    /// nothing).
    pub fn li_probed<P: Probe>(&self, scene: &Scene, ray: Ray, probe: &mut P) -> Color {
        let hit = probe.intersect(scene, &ray);
        probe.ray(RayKind::Camera);
        probe.hit(scene, hit.as_ref(), ray.d);
        probe.end(PathEnd::MaxDepth);
        let Some(si) = hit else {
            return Color::ZERO;
        };
        let to_light = self.position - si.p;
        let d2 = to_light.length_squared();
        let cos = si.frame.n.dot(to_light.unit());
        if !(cos > 0.0 && d2 > 0.0) {
            return Color::ZERO;
        }
        let blocked = probe.occluded(scene, &si.spawn_ray_to(self.position));
        probe.ray(RayKind::Shadow);
        probe.shadow(blocked);
        if blocked {
            return Color::ZERO;
        }
        self.energy * (cos / (4.0 * PI * PI * d2))
    }
}

//! Nori's `normals` integrator: the absolute shading normal of the first surface a camera ray
//! meets, as a colour (black where it meets nothing). A debugging view of geometry and normals.
use super::probe::{PathEnd, Probe, RayKind};
use crate::math::Ray;
use crate::scene::Scene;
use crate::Color;

/// The shading normal's absolute components at the first hit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NormalsIntegrator;

impl NormalsIntegrator {
    /// `|n|` at the surface `ray` meets, or black.
    pub fn li_probed<P: Probe>(&self, scene: &Scene, ray: Ray, probe: &mut P) -> Color {
        let hit = probe.intersect(scene, &ray);
        probe.ray(RayKind::Camera);
        probe.hit(scene, hit.as_ref(), ray.d);
        probe.end(PathEnd::MaxDepth);
        match hit {
            Some(si) => si.frame.n.abs(),
            None => Color::ZERO,
        }
    }
}

//! The course integrators that estimate how open the sky above a surface is, with one ray per
//! sample from the first surface a camera ray meets:
//!
//! - `ao` (Nori's ambient occlusion): `(1 / pi) * integral of V(x, w) cos theta dw` over the
//!   hemisphere of the shading normal, `V` being 1 where a ray leaving `x` meets nothing at
//!   all; estimated by cosine-weighted directions, so each sample is 0 or 1. Black where the
//!   camera ray meets nothing.
//! - `av` (the Wakame assignment's average visibility, `length`): the fraction of the
//!   hemisphere, uniformly weighted, in which a segment of that length meets nothing; white
//!   where the camera ray meets nothing.
use super::probe::{PathEnd, Probe, RayKind};
use crate::math::Ray;
use crate::sampling::warp::{square_to_cosine_hemisphere, square_to_uniform_cone};
use crate::sampling::{Sampler, Stage};
use crate::scene::Scene;
use crate::Color;

/// Which visibility average.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Visibility {
    /// Cosine-weighted, rays of unbounded length (`ao`).
    AmbientOcclusion,
    /// Uniformly weighted, segments of this length (`av`).
    Average {
        /// Length of each visibility segment.
        length: f32,
    },
}

impl Visibility {
    /// One sample's estimate for the surface `ray` meets.
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let hit = probe.intersect(scene, &ray);
        probe.ray(RayKind::Camera);
        probe.hit(scene, hit.as_ref(), ray.d);
        probe.end(PathEnd::MaxDepth);
        let Some(si) = hit else {
            return match self {
                Visibility::AmbientOcclusion => Color::ZERO,
                Visibility::Average { .. } => Color::ONE,
            };
        };
        sampler.start_stage(0, Stage::Bsdf);
        let u = sampler.next_2d();
        let (local, t_max) = match *self {
            Visibility::AmbientOcclusion => (square_to_cosine_hemisphere(u), f32::INFINITY),
            Visibility::Average { length } => (square_to_uniform_cone(u, 0.0), length),
        };
        let mut shadow = si.spawn_ray(si.frame.to_world(local));
        shadow.t_max = t_max;
        let blocked = probe.occluded(scene, &shadow);
        probe.ray(RayKind::Shadow);
        probe.shadow(blocked);
        if blocked {
            Color::ZERO
        } else {
            Color::ONE
        }
    }
}

//! Casting a ray and counting the emission it meets at full weight: the start of the direct
//! and Whitted integrators' work at each ray (neither weighs a hit against another strategy
//! there: direct's camera ray has no emitter sampling to compete with, Whitted never samples
//! emitters toward a surface it then hits).
use super::probe::{Probe, RayKind};
use crate::geometry::Interaction;
use crate::light::emission_along;
use crate::math::{Norm, Ray};
use crate::scene::Scene;
use crate::Color;

/// Casts `ray` (traced as `kind`), tells `probe`, and when `visible` adds the radiance emitted
/// toward its origin by what it meets (an emitting surface, or the environment when it
/// escapes), times `throughput`, to `result`. Returns the hit.
#[inline(always)]
pub(super) fn cast_unweighted<P: Probe>(
    scene: &Scene,
    ray: &Ray,
    kind: RayKind,
    throughput: Color,
    visible: bool,
    result: &mut Color,
    probe: &mut P,
) -> Option<Interaction> {
    let hit = probe.intersect(scene, ray);
    probe.ray(kind);
    probe.hit(scene, hit.as_ref(), ray.d);
    if visible {
        emission_along(
            scene,
            ray.o,
            ray.d.unit(),
            hit.as_ref(),
            false,
            None,
            probe,
            |probe, le, _| {
                *result += throughput * le;
                probe.emission(le, 1.0, throughput * le);
            },
        );
    }
    hit
}

//! Emitter sampling through participating media, for `volpath`: a light is picked and sampled
//! from a surface or medium vertex, and its shadow segment is followed through every `null`
//! surface on the way, each medium it crosses multiplying the light by its transmittance: for a
//! homogeneous medium `exp(-sigma_t d)` computed exactly, for a heterogeneous one estimated by
//! ratio tracking (`Heterogeneous::transmittance`). Any other surface blocks the light, as in
//! Mitsuba 3's `volpath`.
//!
//! Mitsuba 3.9.1 estimates the transmittance by sampling a free flight along the shadow ray and
//! dropping the light when it collides; its expectation is the value used here.
use super::probe::{MediumEvent, Probe, RayKind};
use crate::bsdf::Bsdf;
use crate::geometry::Interaction;
use crate::math::{Norm, Ray};
use crate::medium::Medium;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

/// Crossings of `null` surfaces a shadow ray follows before it gives up (a guard against
/// degenerate geometry; real scenes cross a handful).
const MAX_CROSSINGS: u32 = 256;

/// An emitter sample seen through the media between the vertex and the light.
#[derive(Clone, Copy, Debug)]
pub(super) struct MediumLight {
    /// Unit direction from the vertex toward the light.
    pub wo: Vec3,
    /// Emitted radiance times the transmittance along the way, over the density (selection
    /// included): the unweighted estimate without the vertex's scattering factor.
    pub value: Color,
    /// Solid-angle density of the sample, selection included.
    pub pdf: f32,
    /// Whether the light is a delta distribution.
    pub delta: bool,
    /// The transmittance along the way per channel (for homogeneous media also the probability
    /// that each channel's free flights pass the segment).
    pub pass: Color,
    /// Whether the segment crossed homogeneous media only (no heterogeneous one).
    pub plain: bool,
}

/// Picks a light with the scene's selection, samples it from `it`, and traces the shadow segment
/// through `null` surfaces starting in `medium` (for a surface vertex that bounds media, the
/// caller does not know the side yet: `interface_start` then chooses it by the direction).
/// `None` when nothing arrives.
pub(super) fn sample_light_through<S: Sampler, P: Probe>(
    scene: &Scene,
    it: &Interaction,
    medium: Option<u32>,
    interface_start: bool,
    sampler: &mut S,
    probe: &mut P,
) -> Option<MediumLight> {
    let (idx, sel_pdf) = scene.lights().pick(sampler.next_1d())?;
    let u = sampler.next_2d();
    let es = scene.emitters[idx].sample(&scene.emitter_ctx(), it, u);
    probe.emitter_sample(idx, sel_pdf, es.as_ref());
    let es = es?;
    if !(es.pdf > 0.0) {
        return None;
    }
    let mut medium = medium;
    if interface_start {
        let iface = scene.media.interface(it.shape);
        if iface.is_transition() {
            medium = iface.target(it.ng, es.wo);
        }
    }
    let first = match es.target {
        Some(t) => it.spawn_ray_to(t),
        None => it.spawn_ray(es.wo),
    };
    let (tr, plain) = transmittance_along(scene, first, es.target, medium, sampler, probe)?;
    Some(MediumLight {
        wo: es.wo,
        value: es.weight * tr / sel_pdf,
        pdf: es.pdf * sel_pdf,
        delta: es.delta,
        pass: tr,
        plain,
    })
}

/// Transmittance along the shadow segment `ray` (toward `target`, or to infinity) starting in
/// `medium`, crossing `null` surfaces, and whether it crossed homogeneous media only; `None` when
/// something else blocks it or nothing passes.
fn transmittance_along<S: Sampler, P: Probe>(
    scene: &Scene,
    mut ray: Ray,
    target: Option<Vec3>,
    mut medium: Option<u32>,
    sampler: &mut S,
    probe: &mut P,
) -> Option<(Color, bool)> {
    let mut tr = Color::ONE;
    let mut plain = true;
    for _ in 0..MAX_CROSSINGS {
        let hit = probe.intersect(scene, &ray);
        probe.ray(RayKind::Shadow);
        let len = ray.d.norm();
        let o = ray.o;
        let mut through = |m: Option<u32>, t: f32, probe: &mut P| match m {
            Some(m) => match &scene.media.media[m as usize] {
                Medium::Homogeneous(h) => h.transmittance(ray.d / len, t * len),
                Medium::Heterogeneous(h) => {
                    plain = false;
                    let (tr, n) = h.transmittance(o, ray.d / len, t * len, sampler);
                    for _ in 0..n {
                        probe.medium(MediumEvent::ShadowNullCollision);
                    }
                    tr
                }
            },
            None => Color::ONE,
        };
        let Some(si) = hit else {
            probe.shadow(false);
            tr *= through(medium, ray.t_max, probe);
            return (tr != Color::ZERO).then_some((tr, plain));
        };
        let shape = &scene.shapes[si.shape as usize];
        if !matches!(scene.bsdfs[shape.bsdf as usize], Bsdf::Null(_)) {
            probe.shadow(true);
            return None;
        }
        probe.medium(MediumEvent::ShadowNullCrossing);
        tr *= through(medium, si.t, probe);
        if tr == Color::ZERO {
            probe.shadow(true);
            return None;
        }
        let iface = scene.media.interface(si.shape);
        if iface.is_transition() {
            medium = iface.target(si.ng, ray.d);
        }
        ray = match target {
            Some(t) => si.spawn_ray_to(t),
            None => si.spawn_ray(ray.d),
        };
    }
    probe.shadow(true);
    None
}

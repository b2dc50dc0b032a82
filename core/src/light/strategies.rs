//! The two ways an integrator finds light, shared by every integrator: sampling an emitter from a
//! surface point, and reading what a BSDF-sampled ray ran into. Each returns the densities both
//! strategies would have had, so the caller applies its own weights. Both live with light
//! selection because each needs the probability with which the light it used was picked.
use super::sample::LightSample;
use super::vertex::VertexSelection;
use crate::bsdf::Bsdf;
use crate::emitter::Emitter;
use crate::geometry::{Interaction, ShadingPoint};
use crate::integrator::{Probe, RayKind};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

/// Picks a light (by `sel`, the vertex's own selection, else by the scene's), samples it from
/// `si`, evaluates the BSDF (at `at`, [`Scene::partials`](crate::scene::Scene::partials)) and traces the shadow ray. `None` when
/// nothing arrives (no light, back side, blocked, zero BSDF). The BSDF density is evaluated only
/// when `want_bsdf_pdf` (callers that do not weigh strategies by density skip its cost; it
/// feeds no other value, so skipping it changes nothing else).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn sample_light<S: Sampler, P: Probe>(
    scene: &Scene,
    si: &Interaction,
    bsdf: &Bsdf,
    at: &ShadingPoint,
    wi: Vec3,
    sampler: &mut S,
    want_bsdf_pdf: bool,
    sel: Option<&VertexSelection>,
    probe: &mut P,
) -> Option<LightSample> {
    let (idx, sel_pdf) = if let Some(sel) = sel {
        sel.pick(sampler.next_1d())
    } else if scene.emitters.len() == 1 {
        // Nothing to choose (probability exactly 1 either way): the choice's dimension is
        // skipped, not drawn, so later draws read what they read before.
        sampler.skip_1d();
        (0, 1.0)
    } else {
        scene.lights().pick(sampler.next_1d())?
    };
    let u = sampler.next_2d();
    let es = scene.emitters[idx].sample(&scene.emitter_ctx(), si, u);
    probe.emitter_sample(idx, sel_pdf, es.as_ref());
    let es = es?;
    let wo = si.frame.to_local(es.wo);
    let f = bsdf.eval(wi, wo, at);
    probe.bsdf_eval(f);
    if f == Color::ZERO {
        return None;
    }
    let shadow = match es.target {
        Some(t) => si.spawn_ray_to(t),
        None => si.spawn_ray(es.wo),
    };
    let blocked = probe.occluded(scene, &shadow);
    probe.ray(RayKind::Shadow);
    probe.shadow(blocked);
    if blocked {
        return None;
    }
    let bsdf_pdf = if es.delta || !want_bsdf_pdf {
        0.0
    } else {
        let pdf = bsdf.pdf(wi, wo, at);
        probe.bsdf_pdf(pdf);
        pdf
    };
    Some(LightSample {
        value: f * es.weight / sel_pdf,
        light_pdf: es.pdf * sel_pdf,
        bsdf_pdf,
        delta: es.delta,
    })
}

/// Calls `add(probe, le, light_pdf)` for each emitter a ray from `from` along unit direction `d` sees:
/// the area emitter of the surface it hit, or every environment when it escaped. `light_pdf` is
/// the density emitter sampling from `from` has for that direction (selection included), or 0
/// when `with_pdf` is false (callers that do not weigh strategies skip its cost). The selection
/// probability is `sel`'s, the selection of the vertex at `from`, else the scene's.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn emission_along<P: Probe>(
    scene: &Scene,
    from: Vec3,
    d: Vec3,
    hit: Option<&Interaction>,
    with_pdf: bool,
    sel: Option<&VertexSelection>,
    probe: &mut P,
    mut add: impl FnMut(&mut P, Color, f32),
) {
    match hit {
        Some(si) => {
            let Some(ei) = scene.shapes[si.shape as usize].emitter else {
                return;
            };
            if let Emitter::Area(a) = &scene.emitters[ei as usize] {
                let le = a.eval(si.frame.n, si.wi, si.uv);
                if le != Color::ZERO {
                    let pdf = if with_pdf {
                        a.pdf(&scene.emitter_ctx(), from, si.p, si.ng)
                            * selection_pdf(scene, sel, ei as usize)
                    } else {
                        0.0
                    };
                    add(probe, le, pdf);
                }
            }
        }
        None => {
            for &env in &scene.environments {
                let e = &scene.emitters[env as usize];
                // The radiance and, for weighing, the density: one lookup each in the
                // counters, found together.
                let (le, pdf) = if with_pdf {
                    e.eval_pdf_environment(from, d)
                } else {
                    (e.eval_environment(d), 0.0)
                };
                probe.env_lookup();
                if le != Color::ZERO {
                    let pdf = if with_pdf {
                        probe.env_lookup();
                        pdf * selection_pdf(scene, sel, env as usize)
                    } else {
                        0.0
                    };
                    add(probe, le, pdf);
                }
            }
        }
    }
}

/// The probability that light `i` was picked at the vertex whose selection is `sel` (the
/// scene-wide choice where the vertex has none).
#[inline]
fn selection_pdf(scene: &Scene, sel: Option<&VertexSelection>, i: usize) -> f32 {
    sel.map_or_else(|| scene.lights().pdf(i), |s| s.pdf(i))
}

//! The two ways an integrator finds light, shared by every integrator: sampling an emitter from a
//! surface point, and reading what a BSDF-sampled ray ran into. Each returns the densities both
//! strategies would have had, so the caller applies its own weights.
use crate::bsdf::Bsdf;
use crate::emitter::Emitter;
use crate::geometry::Interaction;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

/// One emitter sample, already tested for visibility.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// `f(wi, wo) cos * Le / (light pdf * selection probability)`: the unweighted estimate.
    pub value: Color,
    /// Density of emitter sampling for this direction, selection included (solid angle).
    pub light_pdf: f32,
    /// Density with which the BSDF would have sampled the same direction.
    pub bsdf_pdf: f32,
    /// Whether the light is a delta distribution (BSDF sampling cannot find it).
    pub delta: bool,
}

/// Picks a light, samples it from `si`, evaluates the BSDF and traces the shadow ray. `None` when
/// nothing arrives (no light, back side, blocked, zero BSDF).
#[inline]
pub fn sample_light<S: Sampler>(
    scene: &Scene,
    si: &Interaction,
    bsdf: &Bsdf,
    wi: Vec3,
    sampler: &mut S,
) -> Option<LightSample> {
    let (idx, sel_pdf) = scene.select_emitter(sampler.next_1d())?;
    let u = sampler.next_2d();
    let es = scene.emitters[idx].sample(&scene.emitter_ctx(), si, u)?;
    let wo = si.frame.to_local(es.wo);
    let f = bsdf.eval(wi, wo, si.uv);
    if f == Color::ZERO {
        return None;
    }
    let shadow = match es.target {
        Some(t) => si.spawn_ray_to(t),
        None => si.spawn_ray(es.wo),
    };
    if scene.occluded(&shadow) {
        return None;
    }
    let bsdf_pdf = if es.delta {
        0.0
    } else {
        bsdf.pdf(wi, wo, si.uv)
    };
    Some(LightSample {
        value: f * es.weight / sel_pdf,
        light_pdf: es.pdf * sel_pdf,
        bsdf_pdf,
        delta: es.delta,
    })
}

/// Calls `add(le, light_pdf)` for each emitter a ray from `from` along unit direction `d` sees:
/// the area emitter of the surface it hit, or every environment when it escaped. `light_pdf` is
/// the density emitter sampling from `from` has for that direction (selection included), or 0
/// when `with_pdf` is false (callers that do not weigh strategies skip its cost).
#[inline]
pub fn emission_along(
    scene: &Scene,
    from: Vec3,
    d: Vec3,
    hit: Option<&Interaction>,
    with_pdf: bool,
    mut add: impl FnMut(Color, f32),
) {
    match hit {
        Some(si) => {
            let Some(ei) = scene.shapes[si.shape as usize].emitter else {
                return;
            };
            if let Emitter::Area(a) = &scene.emitters[ei as usize] {
                let le = a.eval(si.frame.n, si.wi);
                if le != Color::ZERO {
                    let pdf = if with_pdf {
                        a.pdf(&scene.emitter_ctx(), from, si.p, si.ng)
                            * scene.emitter_select_pdf(ei as usize)
                    } else {
                        0.0
                    };
                    add(le, pdf);
                }
            }
        }
        None => {
            for &env in &scene.environments {
                let e = &scene.emitters[env as usize];
                let le = e.eval_environment(d);
                if le != Color::ZERO {
                    let pdf = if with_pdf {
                        e.pdf_environment(from, d) * scene.emitter_select_pdf(env as usize)
                    } else {
                        0.0
                    };
                    add(le, pdf);
                }
            }
        }
    }
}

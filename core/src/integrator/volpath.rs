//! Volumetric path tracer (`volpath`), Mitsuba 3.9.1's: paths through participating media
//! (homogeneous and heterogeneous) and surfaces, with emitter sampling at both kinds of vertex.
//!
//! Scene parameters (`<integrator type="volpath">`): `max_depth` (integer, default -1 =
//! unbounded), `rr_depth` (integer, default 5), `hide_emitters` (boolean, default false), with
//! Mitsuba 3's meaning; they are declared in `scene/src/integrator/tracers.rs`.
//!
//! Each step of the loop, in the medium the path is in (the camera's at first):
//! - Russian roulette once the depth exceeds `rr_depth` (survival `min(max throughput * eta^2,
//!   0.95)`), checked at every step as Mitsuba 3 does;
//! - the ray is cast; inside a medium a free flight is sampled (`medium::sample_free_flight`)
//!   up to the surface it meets, from the colour channel the path chose when it started, and
//!   weighted over the three channels along the whole path (`medium::ChannelRatios`); in a
//!   heterogeneous medium delta tracking samples it (`Heterogeneous::sample_flight`), its null
//!   collisions weighted into the same ratios. A collision is a real scattering event: the depth grows, the
//!   emitters are sampled (when the medium's `sample_emitters` is set) with the phase function
//!   as the scattering factor, and the phase function samples the next direction;
//! - at a surface (or on escaping), emitted light is added; then a `null` surface is crossed
//!   (the depth and the weights of the last real vertex kept), any other is scattered by its
//!   BSDF as in `path`. A surface naming media on its sides moves the path into the one on the
//!   side it leaves toward.
//!
//! Light found by hitting an emitter counts fully after the camera or a chain of delta
//! scatterings (and after a medium vertex that did not sample emitters); otherwise it is
//! weighed by the power heuristic against emitter sampling at the last real scattering vertex,
//! both densities taken at that vertex (transmittance and `null` crossings are common to both
//! strategies and cancel): Mitsuba 3.9.1's rule. With `hide_emitters`, area emitters met by
//! the camera ray outside media are stepped through, as Mitsuba 3 does.
use super::probe::{MediumEvent, PathEnd, Probe, RayKind};
use super::volpath_light::{sample_light_through, MediumLight};
use super::volpath_mis::MediumMis;
use crate::bsdf::Bsdf;
use crate::geometry::{Interaction, ShadingPoint};
use crate::light::emission_along;
use crate::math::{Frame, Norm, Ray};
use crate::medium::{ChannelRatios, Medium};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use glam::{Vec2, Vec3};

/// Surfaces a camera ray steps through while hiding emitters, at most (a guard).
const MAX_SKIPS: u32 = 64;

/// A volumetric path tracer with Mitsuba 3's `volpath` conventions.
#[derive(Clone, Copy, Debug)]
pub struct VolPathIntegrator {
    /// Longest path in real scattering events (`None` = unbounded).
    pub max_depth: Option<u32>,
    /// Depth beyond which Russian roulette applies.
    pub rr_depth: u32,
    /// Whether emitters seen directly by the camera are hidden.
    pub hide_emitters: bool,
    /// How estimates are weighed over channels and strategies (`volpath` or `volpathmis`).
    pub mis: MediumMis,
}

impl Default for VolPathIntegrator {
    fn default() -> Self {
        VolPathIntegrator {
            max_depth: None,
            rr_depth: 5,
            hide_emitters: false,
            mis: MediumMis::Separate,
        }
    }
}

/// The last real scattering vertex: where emitter sampling would have started, and the density
/// of the direction the path took from it.
#[derive(Clone, Copy, Debug)]
struct LastScatter {
    p: Vec3,
    pdf: f32,
    /// The path's channel density ratios there.
    ratios: Color,
}

/// The power heuristic for two densities, 0 where it is not finite.
#[inline]
fn power(a: f32, b: f32) -> f32 {
    let w = (a * a) / (a * a + b * b);
    if w.is_finite() {
        w
    } else {
        0.0
    }
}

impl VolPathIntegrator {
    /// The weight of an emitter sample `ml` taken at a vertex (medium or surface) whose
    /// direction sampling has density `p_dir` toward it: Mitsuba's joint weights over channels
    /// and strategies where they apply (`volpathmis`, a segment through homogeneous media
    /// only), else the power heuristic (1 for a delta light) times the path's channel weight
    /// `mix`.
    #[inline]
    fn light_factor(
        &self,
        joint: bool,
        ml: &MediumLight,
        p_dir: f32,
        channels: &ChannelRatios,
        mix: f32,
    ) -> f32 {
        if joint && ml.plain {
            self.mis
                .emitter_factor(channels.ratios, channels.channel, ml.pdf, p_dir, ml.pass)
        } else {
            let w = if ml.delta { 1.0 } else { power(ml.pdf, p_dir) };
            w * mix
        }
    }
}

/// A point inside a medium, as emitter sampling takes its reference points.
fn medium_point(p: Vec3, wi: Vec3) -> Interaction {
    Interaction {
        p,
        p_err: Vec3::ZERO,
        t: 0.0,
        ng: Vec3::ZERO,
        frame: Frame::from_normal(wi),
        uv: Vec2::ZERO,
        shape: u32::MAX,
        wi,
    }
}

impl VolPathIntegrator {
    /// Radiance along `ray`, telling `probe` about the work done.
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let max_depth = self.max_depth.unwrap_or(u32::MAX);
        let mut ray = ray;
        let mut medium = scene.media.camera;
        let mut throughput = Color::ONE;
        let mut result = Color::ZERO;
        let mut eta = 1.0f32;
        let mut depth = 0u32;
        let mut specular_chain = !self.hide_emitters;
        let mut last: Option<LastScatter> = None;
        let mut first_ray = true;
        // The channel free flights are drawn from, chosen once per path (only with media).
        let mut channels = if scene.media.is_empty() {
            ChannelRatios::new(0.0)
        } else {
            ChannelRatios::new(sampler.next_1d())
        };
        // The throughput's combined weight over the channels (1 until a chromatic medium).
        let mut mix = 1.0f32;
        let joint = matches!(self.mis, MediumMis::Joint { .. });
        let spectral = self.mis.spectral();
        // Since the last real scattering vertex: each channel's probability of the free flights
        // passing (homogeneous media), and whether only homogeneous media were crossed.
        let mut pass = Color::ONE;
        let mut plain = true;
        loop {
            if throughput == Color::ZERO || !throughput.is_finite() || mix == 0.0 {
                probe.end(PathEnd::ZeroThroughput);
                break;
            }
            if depth > self.rr_depth {
                let q = (throughput.max_element() * mix * eta * eta).min(0.95);
                let survived = sampler.next_1d() < q;
                if survived {
                    throughput /= q;
                }
                probe.roulette(q, survived, throughput);
                if !survived {
                    probe.end(PathEnd::Roulette);
                    break;
                }
            }
            if depth >= max_depth {
                probe.end(PathEnd::MaxDepth);
                break;
            }
            let mut hit = probe.intersect(scene, &ray);
            probe.ray(if first_ray {
                RayKind::Camera
            } else {
                RayKind::Continuation
            });
            first_ray = false;
            probe.hit(scene, hit.as_ref(), ray.d);
            let len = ray.d.norm();
            let d = ray.d / len;
            if let Some(m) = medium {
                let t_max = hit.as_ref().map_or(f32::INFINITY, |si| si.t * len);
                let med = &scene.media.media[m as usize];
                let (scattered, t) = match med {
                    Medium::Homogeneous(h) => {
                        let u = sampler.next_1d();
                        let ff = h.sample_flight(ray.o, d, t_max, channels.channel, u);
                        throughput *= channels.record(&ff);
                        if !ff.scattered {
                            pass *= ff.pdf;
                        }
                        (ff.scattered, ff.t)
                    }
                    Medium::Heterogeneous(h) => {
                        let fl = h.sample_flight(ray.o, d, t_max, &mut channels, sampler);
                        for _ in 0..fl.null_collisions {
                            probe.medium(MediumEvent::NullCollision);
                        }
                        throughput *= fl.weight;
                        plain = false;
                        (fl.scattered, fl.t)
                    }
                };
                mix = if spectral { channels.weight() } else { 1.0 };
                if scattered {
                    probe.medium(MediumEvent::Scatter);
                    depth += 1;
                    if depth >= max_depth || throughput == Color::ZERO {
                        probe.end(PathEnd::MaxDepth);
                        break;
                    }
                    let p = ray.o + d * t;
                    let it = medium_point(p, -d);
                    let phase = med.phase_at(p);
                    if med.sample_emitters() {
                        specular_chain = false;
                        if scene.features.has_emitters {
                            if let Some(ml) =
                                sample_light_through(scene, &it, medium, false, sampler, probe)
                            {
                                let f = phase.eval(-d, ml.wo);
                                let p_dir = if ml.delta { 0.0 } else { phase.pdf(-d, ml.wo) };
                                let fk = f * self.light_factor(joint, &ml, p_dir, &channels, mix);
                                let c = throughput * ml.value * fk;
                                result += c;
                            }
                        }
                    } else {
                        specular_chain = true;
                    }
                    let ps = phase.sample(-d, sampler.next_2d());
                    if !(ps.pdf > 0.0) {
                        probe.end(PathEnd::BsdfSampleFailed);
                        break;
                    }
                    throughput *= ps.weight;
                    last = Some(LastScatter {
                        p,
                        pdf: ps.pdf,
                        ratios: channels.ratios,
                    });
                    pass = Color::ONE;
                    plain = true;
                    ray = Ray::new(p, ps.wo);
                    continue;
                }
                probe.medium(MediumEvent::Pass);
            } else if self.hide_emitters && depth == 0 {
                // Mitsuba 3 steps a camera ray through the area emitters it meets.
                let mut skips = 0;
                while let Some(si) = hit.as_ref() {
                    if scene.shapes[si.shape as usize].emitter.is_none() || skips >= MAX_SKIPS {
                        break;
                    }
                    ray = si.spawn_ray(ray.d);
                    hit = probe.intersect(scene, &ray);
                    probe.ray(RayKind::Continuation);
                    probe.hit(scene, hit.as_ref(), ray.d);
                    skips += 1;
                }
            }
            // Light the ray ran into (an area emitter, or the environment on escaping).
            let visible = !(depth == 0 && self.hide_emitters);
            if visible && (hit.is_some() || scene.features.has_environment) {
                let counts_fully = depth == 0 || specular_chain;
                let (from, prev_pdf, prev_ratios) = match last {
                    Some(l) if !counts_fully => (l.p, l.pdf, l.ratios),
                    _ => (ray.o, 0.0, Color::ONE),
                };
                let joint_here = joint && plain;
                emission_along(
                    scene,
                    from,
                    d,
                    hit.as_ref(),
                    !counts_fully,
                    None,
                    probe,
                    |probe, le, light_pdf| {
                        // The MIS weight, and the factor on the throughput it makes.
                        let (w, k) = if counts_fully {
                            (1.0, mix)
                        } else if joint_here {
                            probe.mis_weight();
                            let k = self.mis.hit_factor(
                                prev_ratios,
                                channels.channel,
                                light_pdf,
                                prev_pdf,
                                pass,
                            );
                            (k, k)
                        } else {
                            probe.mis_weight();
                            let w = power(prev_pdf, light_pdf);
                            (w, w * mix)
                        };
                        let c = throughput * le * k;
                        result += c;
                        probe.emission(le, w, c);
                    },
                );
            }
            let Some(si) = hit else {
                probe.end(PathEnd::Escaped);
                break;
            };
            let shape = &scene.shapes[si.shape as usize];
            let bsdf = &scene.bsdfs[shape.bsdf as usize];
            let iface = scene.media.interface(si.shape);
            if let Bsdf::Null(_) = bsdf {
                // Not a scattering event: the path crosses, the depth unchanged.
                probe.medium(MediumEvent::NullCrossing);
                if iface.is_transition() {
                    medium = iface.target(si.ng, d);
                }
                ray = si.spawn_ray(ray.d);
                continue;
            }
            let traits = scene.bsdf_traits(shape.bsdf);
            let wi = si.frame.to_local(si.wi);
            let g = scene.partials(shape.bsdf, &si, &ray);
            let memo = scene.lookup_memo(shape.bsdf);
            let at = ShadingPoint {
                uv: si.uv,
                partials: g.as_ref(),
                memo: memo.as_ref(),
            };
            if traits.has_smooth && depth + 1 < max_depth && scene.features.has_emitters {
                if let Some(ml) = sample_light_through(scene, &si, medium, true, sampler, probe) {
                    let wo = si.frame.to_local(ml.wo);
                    let f = bsdf.eval(wi, wo, at);
                    probe.bsdf_eval(f);
                    if f != Color::ZERO {
                        let p_dir = if ml.delta {
                            0.0
                        } else {
                            let pdf = bsdf.pdf(wi, wo, at);
                            probe.bsdf_pdf(pdf);
                            probe.mis_weight();
                            pdf
                        };
                        let k = self.light_factor(joint, &ml, p_dir, &channels, mix);
                        result += throughput * f * ml.value * k;
                    }
                }
            }
            let (u1, u2) = traits.draw_sample_inputs(sampler);
            let Some(bs) = bsdf.sample(wi, u1, u2, at) else {
                probe.bsdf_sample(None, Vec3::ZERO, throughput);
                probe.end(PathEnd::BsdfSampleFailed);
                break;
            };
            throughput *= bs.weight;
            eta *= bs.eta;
            depth += 1;
            last = Some(LastScatter {
                p: si.p,
                pdf: bs.pdf,
                ratios: channels.ratios,
            });
            pass = Color::ONE;
            plain = true;
            specular_chain = bs.delta;
            let wo = si.frame.to_world(bs.wo);
            probe.bsdf_sample(Some(&bs), wo, throughput);
            if iface.is_transition() {
                medium = iface.target(si.ng, wo);
            }
            ray = si.spawn_ray(wo);
        }
        result
    }
}

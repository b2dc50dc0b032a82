//! A [`Probe`] that records one sample's path event by event, for `tessera render
//! --debug-pixel` (the driver formats it).
use super::probe::{PathEnd, Probe, RayKind};
use crate::bsdf::BsdfSample;
use crate::emitter::EmitterSample;
use crate::geometry::Interaction;
use crate::light::LightSample;
use crate::math::Ray;
use crate::scene::Scene;
use crate::Color;
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// One step of a path, in the order it happened.
#[derive(Clone, Debug)]
pub enum Event {
    /// The camera sample: film position and ray.
    Camera {
        /// Film position in pixels.
        pos: Vec2,
        /// The camera ray.
        ray: Ray,
    },
    /// A ray was traced.
    Ray(RayKind),
    /// A camera or continuation ray met a surface: a path vertex.
    Vertex(Interaction),
    /// A camera or continuation ray escaped along `dir`.
    Escaped(Vec3),
    /// A shadow ray's outcome.
    Shadow {
        /// Whether it was blocked.
        blocked: bool,
    },
    /// An environment lookup.
    EnvLookup,
    /// Light found by a traced ray.
    Emission {
        /// Emitted radiance.
        le: Color,
        /// MIS (or strategy) weight.
        weight: f32,
        /// Throughput x radiance x weight: what it added.
        contribution: Color,
    },
    /// An emitter was sampled.
    EmitterSample {
        /// Emitter index.
        index: usize,
        /// Probability of picking it.
        select_pdf: f32,
        /// The sample (`None`: the emitter produced none).
        sample: Option<EmitterSample>,
    },
    /// A BSDF evaluation.
    BsdfEval(Color),
    /// A BSDF density evaluation.
    BsdfPdf(f32),
    /// An emitter sample that arrived.
    Light {
        /// The sample.
        sample: LightSample,
        /// Its MIS weight.
        weight: f32,
        /// Throughput x value x weight: what it added.
        contribution: Color,
    },
    /// A MIS weight was computed.
    MisWeight,
    /// A BSDF sample.
    BsdfSample {
        /// The sample (`None`: no direction).
        sample: Option<BsdfSample>,
        /// Sampled direction in world space.
        wo: Vec3,
        /// Throughput after the bounce.
        throughput: Color,
    },
    /// A Russian roulette decision.
    Roulette {
        /// Survival probability.
        q: f32,
        /// Whether the path went on.
        survived: bool,
        /// Throughput after (divided by `q` on survival).
        throughput: Color,
    },
    /// The path stopped.
    End(PathEnd),
}

/// The recorded events of one sample.
#[derive(Clone, Debug, Default)]
pub struct PathRecord {
    /// Events in order.
    pub events: Vec<Event>,
}

impl Probe for PathRecord {
    fn camera(&mut self, pos: Vec2, ray: &Ray) {
        self.events.push(Event::Camera { pos, ray: *ray });
    }
    fn ray(&mut self, kind: RayKind) {
        self.events.push(Event::Ray(kind));
    }
    fn hit(&mut self, _: &Scene, si: Option<&Interaction>, dir: Vec3) {
        self.events.push(match si {
            Some(si) => Event::Vertex(*si),
            None => Event::Escaped(dir),
        });
    }
    fn shadow(&mut self, blocked: bool) {
        self.events.push(Event::Shadow { blocked });
    }
    fn env_lookup(&mut self) {
        self.events.push(Event::EnvLookup);
    }
    fn emission(&mut self, le: Color, weight: f32, contribution: Color) {
        self.events.push(Event::Emission {
            le,
            weight,
            contribution,
        });
    }
    fn emitter_sample(&mut self, index: usize, select_pdf: f32, s: Option<&EmitterSample>) {
        self.events.push(Event::EmitterSample {
            index,
            select_pdf,
            sample: s.copied(),
        });
    }
    fn bsdf_eval(&mut self, f: Color) {
        self.events.push(Event::BsdfEval(f));
    }
    fn bsdf_pdf(&mut self, pdf: f32) {
        self.events.push(Event::BsdfPdf(pdf));
    }
    fn light(&mut self, ls: &LightSample, weight: f32, contribution: Color) {
        self.events.push(Event::Light {
            sample: *ls,
            weight,
            contribution,
        });
    }
    fn mis_weight(&mut self) {
        self.events.push(Event::MisWeight);
    }
    fn bsdf_sample(&mut self, s: Option<&BsdfSample>, wo: Vec3, throughput: Color) {
        self.events.push(Event::BsdfSample {
            sample: s.copied(),
            wo,
            throughput,
        });
    }
    fn roulette(&mut self, q: f32, survived: bool, throughput: Color) {
        self.events.push(Event::Roulette {
            q,
            survived,
            throughput,
        });
    }
    fn end(&mut self, why: PathEnd) {
        self.events.push(Event::End(why));
    }
}

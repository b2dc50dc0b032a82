//! Integrators: a closed enum; each estimates the radiance arriving along one camera ray.
mod aov;
mod direct;
mod mis;
mod moment;
mod normals;
mod path;
mod path_batch;
mod path_state;
mod probe;
mod radiance;
mod record;
mod reuse;
mod reuse_halves;
mod simple;
mod strategy;
mod surfaces_only;
mod tally;
mod unweighted_hit;
mod visibility;
mod volpath;
mod volpath_light;
mod volpath_mis;
mod whitted;

pub use aov::{albedo, Aov, AovIntegrator};
pub use direct::DirectIntegrator;
pub use mis::Heuristic;
pub use moment::{xyz_squared, MomentIntegrator, SRGB_TO_XYZ};
pub use normals::NormalsIntegrator;
pub use path::PathIntegrator;
pub use probe::{Counters, MediumEvent, NoProbe, PathEnd, Probe, RayKind};
pub use radiance::Radiance;
pub use record::{Event, PathRecord};
pub use reuse::{GROUP, GROUP_H, GROUP_W};
pub use simple::SimpleIntegrator;
pub use strategy::Strategy;
pub use tally::RayTally;
pub use visibility::Visibility;
pub use volpath::VolPathIntegrator;
pub use volpath_mis::MediumMis;
pub use whitted::WhittedIntegrator;

use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

/// The light transport algorithms.
#[derive(Clone, Debug)]
pub enum Integrator {
    /// Unidirectional path tracing (`path_mats`, `path_ems`, `path_half`, `path_mis` / `path`).
    Path(PathIntegrator),
    /// Volumetric path tracing through participating media (`volpath`).
    VolPath(VolPathIntegrator),
    /// Direct illumination (`direct`, `direct_ems`, `direct_mats`, `direct_mis`).
    Direct(DirectIntegrator),
    /// Nori's shading normals view (`normals`).
    Normals(NormalsIntegrator),
    /// Nori's point light with shadows (`simple`).
    Simple(SimpleIntegrator),
    /// Ambient occlusion and average visibility (`ao`, `av`).
    Visibility(Visibility),
    /// Nori's Whitted-style ray tracer (`whitted`).
    Whitted(WhittedIntegrator),
    /// One of Mitsuba 3's arbitrary output variables as a colour (the `aov` integrator's
    /// channels).
    Aov(AovIntegrator),
    /// A nested integrator's XYZ or its square (the `moment` integrator's channels).
    Moment(MomentIntegrator<Integrator>),
}

impl Integrator {
    /// Radiance arriving along `ray` (one sample; may be non-finite only through broken input,
    /// which the caller drops and counts).
    #[inline]
    pub fn li<S: Sampler>(&self, scene: &Scene, ray: Ray, sampler: &mut S) -> Color {
        match self {
            Integrator::Path(p) => p.li(scene, ray, sampler),
            Integrator::Direct(d) => d.li(scene, ray, sampler),
            _ => self.li_probed(scene, ray, sampler, &mut NoProbe),
        }
    }

    /// Whether every emitter sample this integrator takes on `scene` is weighed by multiple
    /// importance sampling against BSDF sampling, which reaches every direction light can come
    /// from: then emitter sampling may leave out directions, and the scene's environment maps
    /// may sample by MIS-compensated tables ([`Scene::set_environment_compensation`]). `path`
    /// with the MIS strategy (with or without path reuse: the group estimator shares only the
    /// light reflected at second vertices, each estimated by the path tracer's own MIS-weighted
    /// steps, and light reaching a first vertex from a map is found by that vertex's own
    /// emitter sample and BSDF sample, weighed against each other as without reuse), `volpath`
    /// where it runs the path tracer (no media or `null` surfaces), `direct` with both kinds of
    /// samples, and `moment` around one of those.
    pub fn weighs_light_samples_by_mis(&self, scene: &Scene) -> bool {
        match self {
            Integrator::Path(p) => p.strategy == Strategy::Mis,
            Integrator::VolPath(v) => surfaces_only::as_surface_path(v, scene).is_some(),
            Integrator::Direct(d) => d.emitter_samples > 0 && d.bsdf_samples > 0,
            Integrator::Moment(m) => m.inner.weighs_light_samples_by_mis(scene),
            _ => false,
        }
    }

    /// Whether this integrator may render `scene` with its environment maps sampling by
    /// MIS-compensated tables: it weighs every emitter sample by MIS
    /// ([`Integrator::weighs_light_samples_by_mis`]), or it takes none (surface variables,
    /// normals, ambient occlusion).
    pub fn may_use_compensated_environment(&self, scene: &Scene) -> bool {
        self.weighs_light_samples_by_mis(scene)
            || matches!(
                self,
                Integrator::Aov(_) | Integrator::Normals(_) | Integrator::Visibility(_)
            )
    }
}

/// [`Integrator::li`], telling `probe` about the work done; the same value for any probe.
impl Radiance for Integrator {
    #[inline]
    fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        match self {
            Integrator::Path(p) => p.li_probed(scene, ray, sampler, probe),
            Integrator::Direct(d) => d.li_probed(scene, ray, sampler, probe),
            Integrator::VolPath(v) => match surfaces_only::as_surface_path(v, scene) {
                Some(p) => p.li_probed(scene, ray, sampler, probe),
                None => v.li_probed(scene, ray, sampler, probe),
            },
            Integrator::Normals(n) => n.li_probed(scene, ray, probe),
            Integrator::Simple(s) => s.li_probed(scene, ray, probe),
            Integrator::Visibility(v) => v.li_probed(scene, ray, sampler, probe),
            Integrator::Whitted(w) => w.li_probed(scene, ray, sampler, probe),
            Integrator::Aov(a) => a.li_probed(scene, ray, probe),
            Integrator::Moment(m) => m.li_probed(scene, ray, sampler, probe),
        }
    }
}

//! `volpath` on a scene of surfaces alone: without media or `null` surfaces, a volumetric path
//! is a surface path, and `volpath` renders exactly what `path` renders (same bits, same work)
//! instead of paying for medium bookkeeping that never triggers. Mitsuba 3's two integrators
//! agree in expectation on such scenes; this makes them agree sample for sample.
use super::mis::Heuristic;
use super::path::PathIntegrator;
use super::strategy::Strategy;
use super::volpath::VolPathIntegrator;
use crate::scene::Scene;

/// The path tracer `v` amounts to on `scene`, or `None` when the scene has media or `null`
/// surfaces (which only `volpath` handles).
#[inline]
pub(super) fn as_surface_path(v: &VolPathIntegrator, scene: &Scene) -> Option<PathIntegrator> {
    if !scene.media.is_empty() || scene.features.has_null_bsdfs {
        return None;
    }
    Some(PathIntegrator {
        strategy: Strategy::Mis,
        max_depth: v.max_depth,
        rr_depth: v.rr_depth,
        hide_emitters: v.hide_emitters,
        heuristic: Heuristic::Power,
        reuse: false,
    })
}

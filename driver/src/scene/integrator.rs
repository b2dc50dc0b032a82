//! `<integrator>`: the path tracers by name, with Mitsuba 3's parameters.
//!
//! Names: `path` and `path_mis` (MIS, power heuristic), `path_half` (CS500's 1/2 weights),
//! `path_mats` (BSDF sampling only). Parameters: `max_depth` (integer, default -1 = unbounded),
//! `rr_depth` (integer >= 1, default 5), `hide_emitters` (boolean, default false). A scene
//! without an integrator uses `path`.
use super::util::Result;
use crate::xml::Object;
use tessera_core::integrator::{Integrator, PathIntegrator, Strategy};

/// The strategy an integrator name selects, if it is one.
pub fn integrator_from_name(name: &str) -> Option<Strategy> {
    Some(match name {
        "path" | "path_mis" => Strategy::Mis,
        "path_half" => Strategy::Half,
        "path_mats" => Strategy::Bsdf,
        _ => return None,
    })
}

/// Builds the integrator.
pub fn build_integrator(obj: Option<&Object>) -> Result<Integrator> {
    let Some(obj) = obj else {
        return Ok(Integrator::Path(PathIntegrator::default()));
    };
    let strategy = integrator_from_name(&obj.plugin).ok_or_else(|| {
        obj.error(format!(
            "unknown integrator \"{}\" (known: path, path_mis, path_half, path_mats)",
            obj.plugin
        ))
    })?;
    let max_depth = obj.integer("max_depth", -1)?;
    if max_depth < -1 || max_depth > u32::MAX as i64 {
        return Err(super::util::at_prop(
            obj,
            "max_depth",
            format!("\"max_depth\" must be -1 (unbounded) or at least 0, found {max_depth}"),
        ));
    }
    let rr_depth = obj.integer("rr_depth", 5)?;
    if rr_depth < 1 || rr_depth > u32::MAX as i64 {
        return Err(super::util::at_prop(
            obj,
            "rr_depth",
            format!("\"rr_depth\" must be at least 1, found {rr_depth}"),
        ));
    }
    let hide_emitters = obj.boolean("hide_emitters", false)?;
    obj.check_unused()?;
    Ok(Integrator::Path(PathIntegrator {
        strategy,
        max_depth: (max_depth >= 0).then_some(max_depth as u32),
        rr_depth: rr_depth as u32,
        hide_emitters,
    }))
}

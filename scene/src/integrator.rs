//! `<integrator>`: every integrator by name, with Mitsuba 3's parameters.
//!
//! Path tracers, `path` = `path_mis` (MIS), `path_half`, `path_ems`, `path_mats`: `max_depth`
//! (integer, default -1 = unbounded), `rr_depth` (integer >= 1, default 5), `hide_emitters`
//! (boolean, false), and Tessera's own `heuristic` (string power|balance, default power) and
//! `reuse` (boolean, false: share light among 4x2 pixel groups, `core/src/integrator/reuse.rs`).
//! Direct lighting, `direct` (Mitsuba 3): `shading_samples` (integer, 1), `emitter_samples`,
//! `bsdf_samples` (integers, default shading_samples), `hide_emitters`; `direct_ems`,
//! `direct_mats`, `direct_mis` (Wakame: 1/0, 0/1, 1/1 samples with the balance heuristic) take
//! only `hide_emitters`. Every integrator also takes Tessera's `light_selection` (string
//! contribution|power|uniform, default contribution; read by the scene builder). A scene without
//! an integrator uses `path`.
use super::util::{at_prop, Result};
use crate::xml::Object;
use tessera_core::integrator::{DirectIntegrator, Heuristic, Integrator, PathIntegrator, Strategy};

/// Every integrator name, for messages.
pub const INTEGRATOR_NAMES: &str =
    "path, path_mis, path_half, path_ems, path_mats, direct, direct_ems, direct_mats, direct_mis";

/// An integrator's name and parameters as the scene file gives them; the command line may
/// change the name or the depth and build again.
#[derive(Clone, Debug)]
pub struct IntegratorSpec {
    /// Plugin name.
    pub name: String,
    /// Longest path (`None` = unbounded).
    pub max_depth: Option<u32>,
    /// Russian roulette start depth.
    pub rr_depth: u32,
    /// Hide emitters seen by the camera.
    pub hide_emitters: bool,
    /// Share light among 4x2 pixel groups (path tracers' `reuse`).
    pub reuse: bool,
    /// MIS heuristic, when the file names one.
    pub heuristic: Option<Heuristic>,
    /// Emitter samples (`direct`).
    pub emitter_samples: u32,
    /// BSDF samples (`direct`).
    pub bsdf_samples: u32,
}

impl Default for IntegratorSpec {
    fn default() -> Self {
        IntegratorSpec {
            name: "path".into(),
            max_depth: None,
            rr_depth: 5,
            hide_emitters: false,
            reuse: false,
            heuristic: None,
            emitter_samples: 1,
            bsdf_samples: 1,
        }
    }
}

impl IntegratorSpec {
    /// The integrator, or `None` for an unknown name.
    pub fn build(&self) -> Option<Integrator> {
        let path = |strategy| {
            Integrator::Path(PathIntegrator {
                strategy,
                max_depth: self.max_depth,
                rr_depth: self.rr_depth,
                hide_emitters: self.hide_emitters,
                heuristic: self.heuristic.unwrap_or(Heuristic::Power),
                reuse: self.reuse,
            })
        };
        let direct = |e, b, h| {
            Integrator::Direct(DirectIntegrator {
                emitter_samples: e,
                bsdf_samples: b,
                heuristic: h,
                hide_emitters: self.hide_emitters,
            })
        };
        Some(match self.name.as_str() {
            "path" | "path_mis" => path(Strategy::Mis),
            "path_half" => path(Strategy::Half),
            "path_ems" => path(Strategy::Emitter),
            "path_mats" => path(Strategy::Bsdf),
            "direct" => direct(
                self.emitter_samples,
                self.bsdf_samples,
                self.heuristic.unwrap_or(Heuristic::Power),
            ),
            "direct_ems" => direct(1, 0, Heuristic::Balance),
            "direct_mats" => direct(0, 1, Heuristic::Balance),
            "direct_mis" => direct(1, 1, self.heuristic.unwrap_or(Heuristic::Balance)),
            _ => return None,
        })
    }
}

fn count(obj: &Object, name: &str, default: i64) -> Result<u32> {
    let v = obj.integer(name, default)?;
    if !(0..=1 << 20).contains(&v) {
        return Err(at_prop(
            obj,
            name,
            format!("\"{name}\" must be between 0 and 2^20, found {v}"),
        ));
    }
    Ok(v as u32)
}

/// Reads the integrator element (or the default `path`).
pub fn read_integrator(obj: Option<&Object>) -> Result<IntegratorSpec> {
    let Some(obj) = obj else {
        return Ok(IntegratorSpec::default());
    };
    let mut spec = IntegratorSpec {
        name: obj.plugin.clone(),
        ..Default::default()
    };
    if spec.build().is_none() {
        return Err(obj.error(format!(
            "unknown integrator \"{}\" (known: {INTEGRATOR_NAMES})",
            obj.plugin
        )));
    }
    let is_path = spec.name.starts_with("path");
    if is_path {
        let max_depth = obj.integer("max_depth", -1)?;
        if max_depth < -1 || max_depth > u32::MAX as i64 {
            return Err(at_prop(
                obj,
                "max_depth",
                format!("\"max_depth\" must be -1 (unbounded) or at least 0, found {max_depth}"),
            ));
        }
        spec.max_depth = (max_depth >= 0).then_some(max_depth as u32);
        let rr_depth = obj.integer("rr_depth", 5)?;
        if rr_depth < 1 || rr_depth > u32::MAX as i64 {
            return Err(at_prop(
                obj,
                "rr_depth",
                format!("\"rr_depth\" must be at least 1, found {rr_depth}"),
            ));
        }
        spec.rr_depth = rr_depth as u32;
        spec.reuse = obj.boolean("reuse", false)?;
    }
    if spec.name == "direct" {
        let shading = count(obj, "shading_samples", 1)?;
        spec.emitter_samples = count(obj, "emitter_samples", shading as i64)?;
        spec.bsdf_samples = count(obj, "bsdf_samples", shading as i64)?;
        if spec.emitter_samples + spec.bsdf_samples == 0 {
            return Err(
                obj.error("a direct integrator needs emitter_samples or bsdf_samples above 0")
            );
        }
    }
    if is_path || spec.name == "direct" || spec.name == "direct_mis" {
        spec.heuristic = match obj.string_opt("heuristic")?.as_deref() {
            None => None,
            Some("power") => Some(Heuristic::Power),
            Some("balance") => Some(Heuristic::Balance),
            Some(other) => {
                return Err(at_prop(
                    obj,
                    "heuristic",
                    format!("unknown heuristic \"{other}\" (power, balance)"),
                ))
            }
        };
    }
    spec.hide_emitters = obj.boolean("hide_emitters", false)?;
    obj.check_unused()?;
    Ok(spec)
}

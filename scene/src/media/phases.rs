//! The table of `<phase>` plugins ([`PHASES`]), nested in a `<medium>`: `isotropic`, `hg` and
//! `rayleigh` (`phase.rs`), `tabphase` and `blendphase` (files of their own), and the builder
//! that looks a phase function up in it.
use super::blendphase::BLENDPHASE;
use super::phase::{PhasePlugin, HG, ISOTROPIC, RAYLEIGH};
use super::tabphase::TABPHASE;
use crate::plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::medium::PhaseFunction;

/// Every `<phase type=...>` Tessera knows.
pub static PHASES: &[PhasePlugin] = &[ISOTROPIC, HG, RAYLEIGH, TABPHASE, BLENDPHASE];

/// Builds a phase function and reports unused parameters.
pub(crate) fn build_phase(obj: &Object) -> Result<PhaseFunction> {
    let plugin = plugin::find(PHASES, "phase function", obj)?;
    let p = (plugin.build)(obj, build_phase)?;
    plugin.check_unused(obj)?;
    Ok(p)
}

//! The table of `<phase>` plugins ([`PHASES`]), nested in a `<medium>`: `isotropic`, `hg` and
//! `rayleigh` (`phase.rs`), `tabphase`, `blendphase` and `sggx` (files of their own), and the
//! builders that look a phase function up in it.
use super::blendphase::BLENDPHASE;
use super::phase::{PhasePlugin, HG, ISOTROPIC, RAYLEIGH};
use super::sggx::SGGX;
use super::tabphase::TABPHASE;
use crate::plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::medium::{MediumPhase, PhaseFunction};

/// Every `<phase type=...>` Tessera knows.
pub static PHASES: &[PhasePlugin] = &[ISOTROPIC, HG, RAYLEIGH, TABPHASE, BLENDPHASE, SGGX];

/// Builds a medium's own phase function (which may vary through space) and reports unused
/// parameters.
pub(crate) fn build_medium_phase(obj: &Object) -> Result<MediumPhase> {
    let plugin = plugin::find(PHASES, "phase function", obj)?;
    let p = (plugin.build)(obj, build_phase)?;
    plugin.check_unused(obj)?;
    Ok(p)
}

/// Builds a phase function nested in another (the same everywhere).
pub(crate) fn build_phase(obj: &Object) -> Result<PhaseFunction> {
    match build_medium_phase(obj)? {
        MediumPhase::Fixed(f) => Ok(f),
        MediumPhase::SggxGrid(_) => Err(obj.error(format!(
            "{} varies through space (its S grid's voxels differ): only a medium's own phase \
             function may, not one nested in another",
            obj.describe()
        ))),
    }
}

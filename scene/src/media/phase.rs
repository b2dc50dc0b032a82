//! The `<phase>` plugins ([`PHASES`]), nested in a `<medium>`: `isotropic` and `hg`. Their
//! conventions are in `tessera_core::medium::phase`.
use crate::plugin::{self, Param, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::medium::{HenyeyGreenstein, Isotropic, PhaseFunction};

/// A phase function plugin.
pub(crate) type PhasePlugin = Plugin<fn(&Object) -> Result<PhaseFunction>>;

/// Every `<phase type=...>` Tessera knows.
pub static PHASES: &[PhasePlugin] = &[ISOTROPIC, HG];

/// Builds a phase function and reports unused parameters.
pub(crate) fn build_phase(obj: &Object) -> Result<PhaseFunction> {
    let plugin = plugin::find(PHASES, "phase function", obj)?;
    let p = (plugin.build)(obj)?;
    plugin.check_unused(obj)?;
    Ok(p)
}

/// `isotropic`.
pub(crate) const ISOTROPIC: PhasePlugin = Plugin {
    name: "isotropic",
    aliases: &[],
    doc: "Scattering equally likely in every direction: 1 / (4 pi) per steradian. The phase \
          function of a medium that names none.",
    params: &[],
    nested: "",
    build: |_| Ok(PhaseFunction::Isotropic(Isotropic)),
};

const G: Param = Param::float(
    "g",
    0.8,
    Range::open(-1.0, 1.0),
    "mean cosine of the scattering angle: positive scatters forward, negative backward, 0 is \
     isotropic",
);

/// `hg`.
pub(crate) const HG: PhasePlugin = Plugin {
    name: "hg",
    aliases: &[],
    doc: "Henyey-Greenstein: (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^(3/2)) of the angle between \
          the direction of travel and the scattered direction, sampled exactly.",
    params: &[G],
    nested: "",
    build: |obj| {
        Ok(PhaseFunction::Hg(HenyeyGreenstein {
            g: G.read_f32(obj)?,
        }))
    },
};

//! The simplest `<phase>` plugins, `isotropic`, `hg` and `rayleigh`, and what every phase plugin
//! is (`PhasePlugin`). Their conventions are in `tessera_core::medium::phase`; the table of
//! them all is in `phases.rs`.
use crate::plugin::{Param, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::medium::{HenyeyGreenstein, Isotropic, MediumPhase, PhaseFunction, Rayleigh};

/// What builds a nested `<phase>` (handed to the plugins that nest phase functions, so that
/// their files do not depend on this table).
pub(crate) type PhaseNest = fn(&Object) -> Result<PhaseFunction>;

/// A phase function plugin: it builds a function that may vary through space (only `sggx`
/// does).
pub(crate) type PhasePlugin = Plugin<fn(&Object, PhaseNest) -> Result<MediumPhase>>;

/// `isotropic`.
pub(crate) const ISOTROPIC: PhasePlugin = Plugin {
    name: "isotropic",
    aliases: &[],
    doc: "Scattering equally likely in every direction: 1 / (4 pi) per steradian. The phase \
          function of a medium that names none.",
    params: &[],
    nested: "",
    build: |_, _| Ok(MediumPhase::Fixed(PhaseFunction::Isotropic(Isotropic))),
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
    build: |obj, _| {
        Ok(MediumPhase::Fixed(PhaseFunction::Hg(HenyeyGreenstein {
            g: G.read_f32(obj)?,
        })))
    },
};

/// `rayleigh`.
pub(crate) const RAYLEIGH: PhasePlugin = Plugin {
    name: "rayleigh",
    aliases: &[],
    doc: "Rayleigh scattering by particles much smaller than the wavelength: 3 (1 + cos^2) / \
          (16 pi) of the scattering angle, the same forward and backward, sampled exactly. The \
          same for every colour channel (as in Mitsuba 3's non-polarised modes).",
    params: &[],
    nested: "",
    build: |_, _| Ok(MediumPhase::Fixed(PhaseFunction::Rayleigh(Rayleigh))),
};

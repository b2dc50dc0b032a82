//! The `homogeneous` `<medium>` plugin. Its conventions are in
//! `tessera_core::medium::homogeneous`.
use super::common::{nested_phase, MediumPlugin, HAS_SPECTRAL_EXTINCTION, SAMPLE_EMITTERS, SCALE};
use super::volumes::{read_volume, volume_param};
use crate::plugin::{Default, Param, Plugin, Range};
use tessera_core::medium::{Homogeneous, Medium, MediumPhase};

const SIGMA_T: Param = Param::rgb(
    "sigma_t",
    Default::Rgb([1.0; 3]),
    Range::NonNegative,
    "extinction coefficient per unit of scene length (a float, or rgb for one per channel)",
);
const ALBEDO: Param = volume_param(
    "albedo",
    0.75,
    "single-scattering albedo: the fraction of extinction that scatters (a float or rgb, or a \
     <volume> looked up where a collision happens)",
);

/// `homogeneous`.
pub(crate) const HOMOGENEOUS: MediumPlugin = Plugin {
    name: "homogeneous",
    aliases: &[],
    doc: "A medium of constant extinction and albedo: light travelling a distance d keeps \
          exp(-sigma_t d), and of what collides a fraction albedo scatters by the phase \
          function. A shape bounds it by naming it as its interior or exterior (with the `null` \
          BSDF for an invisible boundary); a sensor names the medium it sits in. Rendered by \
          `volpath`.",
    params: &[
        SIGMA_T,
        ALBEDO,
        SCALE,
        SAMPLE_EMITTERS,
        HAS_SPECTRAL_EXTINCTION,
    ],
    nested: "an optional <phase> (default isotropic)",
    build: |obj| {
        // Checked and marked read; its declared warning is all it does.
        HAS_SPECTRAL_EXTINCTION.read_bool(obj)?;
        let sigma_t = SIGMA_T.read_color(obj)? * SCALE.read_f32(obj)?;
        if !sigma_t.is_finite() {
            return Err(SIGMA_T.out_of_range(obj, "finite after scale", sigma_t.max_element()));
        }
        let phase = match nested_phase(obj)? {
            MediumPhase::Fixed(f) => f,
            MediumPhase::SggxGrid(_) => {
                return Err(obj.error(format!(
                    "{} has an sggx phase function whose S varies through space, which would \
                     make its extinction vary: use a heterogeneous medium",
                    obj.describe()
                )))
            }
        };
        Ok(Medium::Homogeneous(Box::new(Homogeneous {
            sigma_t,
            albedo: read_volume(obj, &ALBEDO)?,
            sample_emitters: SAMPLE_EMITTERS.read_bool(obj)?,
            phase,
        })))
    },
};

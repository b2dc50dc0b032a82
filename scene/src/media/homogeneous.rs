//! The `<medium>` plugins ([`MEDIA`]): `homogeneous`. Its conventions are in
//! `tessera_core::medium::homogeneous`; Mitsuba 3's `heterogeneous` (voxel grids) is refused
//! with a located error naming it.
use super::phase::build_phase;
use crate::plugin::{self, Default, Param, Plugin, Range};
use crate::util::Result;
use crate::xml::{Kind, Object};
use tessera_core::medium::{Homogeneous, Medium, PhaseFunction};

/// A medium plugin.
pub(crate) type MediumPlugin = Plugin<fn(&Object) -> Result<Medium>>;

/// Every `<medium type=...>` Tessera knows.
pub static MEDIA: &[MediumPlugin] = &[HOMOGENEOUS];

/// Builds a medium (with its nested phase function) and reports unused parameters.
pub(crate) fn build_medium(obj: &Object) -> Result<Medium> {
    let plugin = plugin::find(MEDIA, "medium", obj)?;
    let m = (plugin.build)(obj)?;
    plugin.check_unused(obj)?;
    Ok(m)
}

const SIGMA_T: Param = Param::rgb(
    "sigma_t",
    Default::Rgb([1.0; 3]),
    Range::NonNegative,
    "extinction coefficient per unit of scene length (a float, or rgb for one per channel)",
);
const ALBEDO: Param = Param::rgb(
    "albedo",
    Default::Rgb([0.75; 3]),
    Range::NonNegative,
    "single-scattering albedo: the fraction of extinction that scatters (a float or rgb)",
);
const SCALE: Param = Param::float(
    "scale",
    1.0,
    Range::NonNegative,
    "factor on sigma_t (for data in other units)",
);
const SAMPLE_EMITTERS: Param = Param::boolean(
    "sample_emitters",
    true,
    "whether scattering events in the medium sample emitters (shadow rays from inside it)",
);

const HAS_SPECTRAL_EXTINCTION: Param = Param::boolean(
    "has_spectral_extinction",
    true,
    "has no effect: Mitsuba 3's hint that sigma_t differs per channel; free flights are weighed \
     over the channels either way",
)
.ignored();

/// The phase function nested in `obj` (default `isotropic`); one at most.
fn nested_phase(obj: &Object) -> Result<PhaseFunction> {
    let mut phases = obj.children_of(Kind::Phase);
    let Some(first) = phases.next() else {
        return Ok(PhaseFunction::default());
    };
    if let Some(second) = phases.next() {
        return Err(crate::error::InputError::at(
            &second.loc,
            format!(
                "{} has more than one phase function (one at most, as in Mitsuba 3)",
                obj.describe()
            ),
        ));
    }
    first.mark_used();
    build_phase(&first.obj)
}

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
        Ok(Medium::Homogeneous(Homogeneous {
            sigma_t,
            albedo: ALBEDO.read_color(obj)?,
            sample_emitters: SAMPLE_EMITTERS.read_bool(obj)?,
            phase: nested_phase(obj)?,
        }))
    },
};

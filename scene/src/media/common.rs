//! What the `<medium>` plugins share: the builder's type, the parameters both media take
//! (`scale`, `sample_emitters`, `has_spectral_extinction`) and the nested phase function.
use super::phases::build_medium_phase;
use crate::plugin::{Param, Plugin, Range};
use crate::util::Result;
use crate::xml::{Kind, Object};
use tessera_core::medium::{Medium, MediumPhase, PhaseFunction};

/// A medium plugin.
pub(crate) type MediumPlugin = Plugin<fn(&Object) -> Result<Medium>>;

/// `scale`: a factor on the extinction.
pub(crate) const SCALE: Param = Param::float(
    "scale",
    1.0,
    Range::NonNegative,
    "factor on sigma_t (for data in other units)",
);
/// `sample_emitters`.
pub(crate) const SAMPLE_EMITTERS: Param = Param::boolean(
    "sample_emitters",
    true,
    "whether scattering events in the medium sample emitters (shadow rays from inside it)",
);

/// `has_spectral_extinction` (without effect).
pub(crate) const HAS_SPECTRAL_EXTINCTION: Param = Param::boolean(
    "has_spectral_extinction",
    true,
    "has no effect: Mitsuba 3's hint that sigma_t differs per channel; free flights are weighed \
     over the channels either way",
)
.ignored();

/// The phase function nested in `obj` (default `isotropic`); one at most.
pub(crate) fn nested_phase(obj: &Object) -> Result<MediumPhase> {
    let mut phases = obj.children_of(Kind::Phase);
    let Some(first) = phases.next() else {
        return Ok(MediumPhase::Fixed(PhaseFunction::default()));
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
    build_medium_phase(&first.obj)
}

//! The `tabphase` `<phase>` plugin: a phase function given as a list of values over the cosine
//! of the scattering angle. The list is read as Mitsuba 3 reads it: a string of numbers
//! separated by commas and/or spaces (empty items skipped), at least two, none negative, not all
//! zero. The model is `tessera_core::medium::Tabulated`.
use super::phase::{PhaseNest, PhasePlugin};
use crate::error::InputError;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::{at_prop, Result};
use crate::xml::Object;
use tessera_core::medium::{MediumPhase, PhaseFunction, TableError, Tabulated};

const VALUES: Param = Param::new(
    "values",
    ParamType::String,
    Default::Required,
    Range::Note("at least two non-negative numbers, not all zero, separated by commas or spaces"),
    "the function's values at evenly spaced cosines of the scattering angle from -1 (backward) \
     to 1 (forward), interpolated linearly between them and normalised to integrate to 1",
);

/// `tabphase`.
pub(crate) const TABPHASE: PhasePlugin = Plugin {
    name: "tabphase",
    aliases: &[],
    doc: "A phase function tabulated over the cosine of the scattering angle (the angle between \
          the direction of travel and the scattered direction), linear between the entries and \
          uniform in azimuth; sampled exactly through the table's cumulative distribution.",
    params: &[VALUES],
    nested: "",
    build: build_tabphase,
};

fn build_tabphase(obj: &Object, _: PhaseNest) -> Result<MediumPhase> {
    let text = VALUES.read_string(obj)?;
    let err = |msg: String| -> InputError { at_prop(obj, "values", msg) };
    let mut values = Vec::new();
    for item in text
        .split([',', ' ', '\t', '\n', '\r'])
        .filter(|s| !s.is_empty())
    {
        let v: f32 = item.parse().map_err(|_| {
            err(format!(
                "\"values\" of {}: \"{item}\" is not a number",
                obj.describe()
            ))
        })?;
        values.push(v);
    }
    let table = Tabulated::new(&values).map_err(|e| {
        err(match e {
            TableError::TooFew => format!(
                "\"values\" of {} needs at least two numbers, found {}",
                obj.describe(),
                values.len()
            ),
            TableError::BadValue(i) => format!(
                "\"values\" of {} must be finite and non-negative, found {} (entry {})",
                obj.describe(),
                values[i],
                i + 1
            ),
            TableError::NoMass => format!("\"values\" of {} are all zero", obj.describe()),
        })
    })?;
    Ok(MediumPhase::Fixed(PhaseFunction::Tabulated(Box::new(
        table,
    ))))
}

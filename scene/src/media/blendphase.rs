//! The `blendphase` `<phase>` plugin: two nested phase functions mixed by a weight. Mitsuba 3.9.1
//! reads the weight as a volume and requires it; here it must be the same everywhere (a float, or
//! a `constvolume` of one value), and a volume that varies is refused with a located error. The
//! two functions are taken in file order: weight 0 is the first alone, 1 the second alone (as
//! Mitsuba 3.9.1 does). The model is `tessera_core::medium::Blend`.
use super::phase::{PhaseNest, PhasePlugin};
use super::volumes::build_volume;
use crate::error::InputError;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::Result;
use crate::xml::{Kind, Object};
use tessera_core::medium::{Blend, MediumPhase, PhaseFunction, VolumeData};

const WEIGHT: Param = Param::new(
    "weight",
    ParamType::Volume,
    Default::Required,
    Range::Unit,
    "share of the second phase function: (1 - weight) first + weight second; a float or a \
     constvolume (a volume that varies through space is refused)",
);

/// `blendphase`.
pub(crate) const BLENDPHASE: PhasePlugin = Plugin {
    name: "blendphase",
    aliases: &[],
    doc: "A linear blend of two phase functions, sampled by choosing one of them with its share \
          and weighted by the blend's value over its density.",
    params: &[WEIGHT],
    nested: "exactly two <phase>, in file order the first and the second",
    build: build_blendphase,
};

fn read_weight(obj: &Object) -> Result<f32> {
    let value = if obj.has("weight") && obj.prop("weight").is_none() {
        let child = obj.child("weight").expect("a named child exists");
        if child.obj.kind != Kind::Volume {
            return Err(InputError::at(
                &child.loc,
                format!(
                    "\"weight\" of {} must be a float or a volume, found {}",
                    obj.describe(),
                    child.obj.describe()
                ),
            ));
        }
        let volume = build_volume(&child.obj)?;
        match volume.data {
            VolumeData::Constant(c) if c.x == c.y && c.y == c.z => f64::from(c.x),
            _ => {
                return Err(InputError::at(
                    &child.loc,
                    format!(
                        "\"weight\" of {} must be the same everywhere (a float or a constvolume \
                         of one value): a weight that varies is not read yet",
                        obj.describe()
                    ),
                ))
            }
        }
    } else {
        obj.float_opt("weight")?
            .ok_or_else(|| obj.missing("weight"))?
    };
    if !(0.0..=1.0).contains(&value) {
        return Err(WEIGHT.out_of_range(obj, "in [0, 1]", value));
    }
    Ok(value as f32)
}

fn build_blendphase(obj: &Object, nest: PhaseNest) -> Result<MediumPhase> {
    let weight = read_weight(obj)?;
    let kids: Vec<_> = obj.children_of(Kind::Phase).collect();
    if kids.len() != 2 {
        return Err(obj.error(format!(
            "{} needs exactly two nested phase functions, found {}",
            obj.describe(),
            kids.len()
        )));
    }
    let mut built = Vec::with_capacity(2);
    for k in kids {
        k.mark_used();
        built.push(nest(&k.obj)?);
    }
    let second = built.pop().expect("two phase functions");
    let first = built.pop().expect("two phase functions");
    Ok(MediumPhase::Fixed(PhaseFunction::Blend(Blend {
        weight,
        first: Box::new(first),
        second: Box::new(second),
    })))
}

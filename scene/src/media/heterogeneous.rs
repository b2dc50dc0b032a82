//! The `heterogeneous` `<medium>` plugin: extinction and albedo from volumes (a `gridvolume`,
//! a `constvolume`, or a float or rgb). Its conventions are in
//! `tessera_core::medium::heterogeneous`.
use super::common::{nested_phase, MediumPlugin, HAS_SPECTRAL_EXTINCTION, SAMPLE_EMITTERS, SCALE};
use super::volumes::{read_volume, volume_param};
use crate::plugin::{Param, Plugin};
use tessera_core::medium::{Heterogeneous, Medium};

const SIGMA_T: Param = volume_param(
    "sigma_t",
    1.0,
    "extinction per unit of scene length: a <volume> (its box bounds the medium), or a float or \
     rgb (a constant over the unit cube, as in Mitsuba 3)",
);
const ALBEDO: Param = volume_param(
    "albedo",
    0.75,
    "single-scattering albedo: a <volume>, or a float or rgb",
);

/// `heterogeneous`.
pub(crate) const HETEROGENEOUS: MediumPlugin = Plugin {
    name: "heterogeneous",
    aliases: &[],
    doc: "A medium whose extinction and albedo vary through space, given by volumes. It has \
          extinction only inside its sigma_t volume's box (as in Mitsuba 3); the shape that \
          names it as interior bounds where paths enter it. volpath samples distances by delta \
          tracking against per-cell majorants and estimates shadow-ray transmittance by ratio \
          tracking.",
    params: &[
        SIGMA_T,
        ALBEDO,
        SCALE,
        SAMPLE_EMITTERS,
        HAS_SPECTRAL_EXTINCTION,
    ],
    nested: "an optional <phase> (default isotropic); <volume> objects named sigma_t and albedo",
    build: |obj| {
        HAS_SPECTRAL_EXTINCTION.read_bool(obj)?;
        let sigma_t = read_volume(obj, &SIGMA_T)?;
        let scale = SCALE.read_f32(obj)?;
        let top = sigma_t.max_value() * scale;
        if !top.is_finite() {
            return Err(SIGMA_T.out_of_range(obj, "finite after scale", top));
        }
        let albedo = read_volume(obj, &ALBEDO)?;
        Ok(Medium::Heterogeneous(Box::new(Heterogeneous::new(
            sigma_t,
            albedo,
            scale,
            nested_phase(obj)?,
            SAMPLE_EMITTERS.read_bool(obj)?,
        ))))
    },
};

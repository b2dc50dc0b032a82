//! The integrator family's table, the reader that finds a plugin by name, and the step that
//! makes the core integrator from a spec: the one file that knows every integrator plugin.
use super::aov::{AOV, MOMENT};
use super::spec::{IntegratorPlugin, IntegratorSpec, Layer, LayerSource};
use super::tracers::{
    AO, AV, DIRECT, DIRECT_EMS, DIRECT_MATS, DIRECT_MIS, NORMALS, PATH, PATH_EMS, PATH_HALF,
    PATH_MATS, SIMPLE, VOLPATH, VOLPATHMIS, WHITTED,
};
use crate::plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::integrator::{AovIntegrator, Integrator, MomentIntegrator};

/// Every `<integrator type=...>` Tessera knows.
pub static INTEGRATORS: &[IntegratorPlugin] = &[
    PATH,
    PATH_HALF,
    PATH_EMS,
    PATH_MATS,
    VOLPATH,
    VOLPATHMIS,
    DIRECT,
    DIRECT_EMS,
    DIRECT_MATS,
    DIRECT_MIS,
    MOMENT,
    AOV,
    WHITTED,
    SIMPLE,
    AO,
    AV,
    NORMALS,
];

/// Reads the integrator element (or the default `path`) and reports unused parameters.
pub(crate) fn read_integrator(obj: Option<&Object>) -> Result<IntegratorSpec> {
    let Some(obj) = obj else {
        return Ok(IntegratorSpec::default());
    };
    let plugin = plugin::find(INTEGRATORS, "integrator", obj)?;
    let mut spec = IntegratorSpec {
        name: obj.plugin.clone(),
        ..Default::default()
    };
    (plugin.build.read)(obj, &mut spec, read_integrator)?;
    plugin.check_unused(obj)?;
    Ok(spec)
}

/// Every integrator name, for messages.
pub(crate) fn integrator_names() -> String {
    plugin::names(INTEGRATORS)
}

impl IntegratorSpec {
    /// The integrator, or `None` for a name that is not an integrator of its own (unknown, a
    /// wrapper such as `moment`, or `simple` without the light its file must give).
    pub fn build(&self) -> Option<Integrator> {
        let plugin = INTEGRATORS.iter().find(|p| p.is(&self.name))?;
        if plugin.name == SIMPLE.name && self.point_light.is_none() {
            return None;
        }
        Some((plugin.build.make?)(self))
    }
}

impl Layer {
    /// The core integrator that renders the layer (`None` only for a nested spec that builds
    /// nothing, which the loader has already refused).
    pub fn build(&self) -> Option<Integrator> {
        Some(match &self.source {
            LayerSource::Nested(spec) => spec.build()?,
            LayerSource::Aov(aov) => Integrator::Aov(AovIntegrator::new(*aov, 1)),
            LayerSource::Moment { nested, square } => Integrator::Moment(MomentIntegrator {
                inner: Box::new(nested.build()?),
                square: *square,
            }),
        })
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn declarations_match_what_the_builders_read() {
        crate::plugin::check::check_family(
            super::INTEGRATORS,
            crate::xml::Kind::Integrator,
            |obj| super::read_integrator(Some(obj)),
            |name| match name {
                "moment" => "<integrator type=\"path\"/>".into(),
                "aov" => "<string name=\"aovs\" value=\"dd:depth\"/>".into(),
                "simple" => "<point name=\"position\" value=\"0, 1, 0\"/>\
                             <rgb name=\"energy\" value=\"1\"/>"
                    .into(),
                _ => String::new(),
            },
            &[],
        );
    }
}

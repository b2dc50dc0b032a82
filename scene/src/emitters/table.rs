//! The emitter family's table and its builder.
use super::{area, delta, infinite, projector, EmitterPlugin};
use crate::plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::emitter::Emitter;

/// Every `<emitter type=...>` Tessera knows.
pub static EMITTERS: &[EmitterPlugin] = &[
    area::AREA,
    delta::POINT,
    delta::SPOT,
    projector::PROJECTOR,
    delta::DIRECTIONAL,
    infinite::CONSTANT,
    infinite::ENVMAP,
    infinite::DISTANTDISK,
];

/// Builds an emitter: at scene level (`shape` is `None`) or nested in shape `shape` (which
/// only an area light may be), and reports unused parameters.
pub(crate) fn build_emitter(obj: &Object, shape: Option<u32>) -> Result<Emitter> {
    if shape.is_some() && obj.plugin != area::AREA.name {
        return Err(obj.error(format!(
            "a shape can only carry an \"area\" emitter, found \"{}\"",
            obj.plugin
        )));
    }
    let plugin = plugin::find(EMITTERS, "emitter", obj)?;
    let e = (plugin.build)(obj, shape)?;
    plugin.check_unused(obj)?;
    Ok(e)
}

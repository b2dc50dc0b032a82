//! The sensor family's table and its builder: the one file that knows every sensor plugin.
use super::{SensorParts, SensorPlugin, ORTHOGRAPHIC, PERSPECTIVE, THINLENS};
use crate::plugin;
use crate::util::Result;
use crate::xml::Object;

/// Every `<sensor type=...>` Tessera knows.
pub static SENSORS: &[SensorPlugin] = &[PERSPECTIVE, THINLENS, ORTHOGRAPHIC];

/// Builds the sensor and reports unused parameters.
pub(crate) fn build_sensor(obj: &Object, warnings: &mut Vec<String>) -> Result<SensorParts> {
    let plugin = plugin::find(SENSORS, "sensor", obj)?;
    let s = (plugin.build)(obj, warnings)?;
    plugin.check_unused(obj)?;
    Ok(s)
}

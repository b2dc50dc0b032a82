//! The table of `<medium>` plugins ([`MEDIA`]) and the builder that looks a medium up in it.
use super::common::MediumPlugin;
use super::heterogeneous::HETEROGENEOUS;
use super::homogeneous::HOMOGENEOUS;
use crate::plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::medium::Medium;

/// Every `<medium type=...>` Tessera knows.
pub static MEDIA: &[MediumPlugin] = &[HOMOGENEOUS, HETEROGENEOUS];

/// Builds a medium (with its nested phase function and volumes) and reports unused parameters.
pub(crate) fn build_medium(obj: &Object) -> Result<Medium> {
    let plugin = plugin::find(MEDIA, "medium", obj)?;
    let m = (plugin.build)(obj)?;
    plugin.check_unused(obj)?;
    Ok(m)
}

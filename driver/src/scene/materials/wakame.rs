//! Not implemented yet.
use super::Result;
use crate::xml::Object;
use tessera_core::bsdf::Bsdf;

/// Builds the plugins of this file.
pub fn build(obj: &Object) -> Result<Bsdf> {
    Err(obj.error(format!("bsdf \"{}\" is not implemented yet", obj.plugin)))
}

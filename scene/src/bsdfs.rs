//! `<bsdf>` objects to core BSDFs, each built once however often it is referenced. The
//! builders for each plugin live in `materials/`.
use super::materials::build_bsdf;
use super::util::Result;
use crate::xml::Object;
use std::collections::HashMap;
use std::rc::Rc;
use tessera_core::bsdf::{Bsdf, Diffuse};
use tessera_core::texture::Texture;

/// The BSDF table under construction.
#[derive(Default)]
pub(crate) struct Bsdfs {
    /// Built BSDFs.
    pub list: Vec<Bsdf>,
    /// The plugin name each was built from (as the file wrote it).
    pub names: Vec<String>,
    by_object: HashMap<*const Object, u32>,
    default: Option<u32>,
    default_emitter: Option<u32>,
}

impl Bsdfs {
    /// Index of the BSDF for `obj`, building it on first use.
    pub(crate) fn index_of(&mut self, obj: &Rc<Object>) -> Result<u32> {
        let key = Rc::as_ptr(obj);
        if let Some(&i) = self.by_object.get(&key) {
            return Ok(i);
        }
        let b = build_bsdf(obj)?;
        let i = self.list.len() as u32;
        self.list.push(b);
        self.names.push(obj.plugin.clone());
        self.by_object.insert(key, i);
        Ok(i)
    }
    /// Adds a BSDF built elsewhere (an OBJ's MTL material, named `name`) and returns its index.
    pub fn push(&mut self, b: Bsdf, name: String) -> u32 {
        self.list.push(b);
        self.names.push(name);
        self.list.len() as u32 - 1
    }
    /// The default BSDF of shapes without one: one-sided diffuse, reflectance 0.5, or 0 for a
    /// shape that emits (both as Mitsuba 3 does; measured).
    pub(crate) fn default_index(&mut self, emitting: bool) -> u32 {
        let (slot, albedo) = if emitting {
            (&mut self.default_emitter, 0.0)
        } else {
            (&mut self.default, 0.5)
        };
        if let Some(i) = *slot {
            return i;
        }
        self.list.push(Bsdf::Diffuse(Diffuse {
            reflectance: Texture::constant(albedo),
        }));
        self.names.push("diffuse (default)".into());
        let i = self.list.len() as u32 - 1;
        *slot = Some(i);
        i
    }
}

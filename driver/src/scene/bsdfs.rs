//! `<bsdf>` objects to core BSDFs, each built once however often it is referenced.
//!
//! `diffuse`: `reflectance` (rgb, default 0.5). `twosided`: one nested bsdf (both sides) or two
//! (front, back).
use super::util::{color, Result};
use crate::xml::{Kind, Object};
use std::collections::HashMap;
use std::rc::Rc;
use tessera_core::bsdf::{Bsdf, Diffuse, TwoSided};

/// The BSDF table under construction.
#[derive(Default)]
pub struct Bsdfs {
    /// Built BSDFs.
    pub list: Vec<Bsdf>,
    by_object: HashMap<*const Object, u32>,
    default: Option<u32>,
    default_emitter: Option<u32>,
}

impl Bsdfs {
    /// Index of the BSDF for `obj`, building it on first use.
    pub fn index_of(&mut self, obj: &Rc<Object>) -> Result<u32> {
        let key = Rc::as_ptr(obj);
        if let Some(&i) = self.by_object.get(&key) {
            return Ok(i);
        }
        let b = build_bsdf(obj)?;
        let i = self.list.len() as u32;
        self.list.push(b);
        self.by_object.insert(key, i);
        Ok(i)
    }
    /// The default BSDF of shapes without one: one-sided diffuse, reflectance 0.5, or 0 for a
    /// shape that emits (both as Mitsuba 3 does; measured).
    pub fn default_index(&mut self, emitting: bool) -> u32 {
        let (slot, albedo) = if emitting {
            (&mut self.default_emitter, 0.0)
        } else {
            (&mut self.default, 0.5)
        };
        if let Some(i) = *slot {
            return i;
        }
        self.list.push(Bsdf::Diffuse(Diffuse {
            reflectance: glam::Vec3::splat(albedo),
        }));
        let i = self.list.len() as u32 - 1;
        *slot = Some(i);
        i
    }
}

/// Builds one BSDF (recursively for wrappers).
pub fn build_bsdf(obj: &Object) -> Result<Bsdf> {
    let b = match obj.plugin.as_str() {
        "diffuse" => Bsdf::Diffuse(Diffuse {
            reflectance: color(obj, "reflectance", [0.5; 3])?,
        }),
        "twosided" => {
            let inner: Vec<_> = obj
                .children
                .iter()
                .filter(|c| c.obj.kind == Kind::Bsdf)
                .collect();
            let (front, back) = match inner.as_slice() {
                [one] => {
                    one.mark_used();
                    let b = build_bsdf(&one.obj)?;
                    (b.clone(), b)
                }
                [f, b] => {
                    f.mark_used();
                    b.mark_used();
                    (build_bsdf(&f.obj)?, build_bsdf(&b.obj)?)
                }
                _ => return Err(obj.error("a twosided bsdf needs one or two nested bsdfs")),
            };
            Bsdf::TwoSided(TwoSided {
                front: Box::new(front),
                back: Box::new(back),
            })
        }
        other => {
            return Err(obj.error(format!(
                "unknown bsdf \"{other}\" (known: diffuse, twosided)"
            )))
        }
    };
    obj.check_unused()?;
    Ok(b)
}

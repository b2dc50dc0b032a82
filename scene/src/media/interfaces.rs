//! The scene's media as indices: each `<medium>` built once however often it is referenced, the
//! media a shape names on its sides (`interior`, `exterior`) and the medium a sensor names.
use super::table::build_medium;
use crate::error::{InputError, Loc};
use crate::util::Result;
use crate::xml::{Child, Kind, Object};
use std::collections::HashMap;
use std::rc::Rc;
use tessera_core::medium::{Medium, MediumInterface};

/// The media table under construction.
#[derive(Default)]
pub(crate) struct Media {
    /// Built media.
    pub list: Vec<Medium>,
    /// Where each was declared (for messages about the scene's media).
    pub locs: Vec<Loc>,
    by_object: HashMap<*const Object, u32>,
}

impl Media {
    /// Index of the medium for `obj`, building it on first use.
    pub(crate) fn index_of(&mut self, obj: &Rc<Object>) -> Result<u32> {
        let key = Rc::as_ptr(obj);
        if let Some(&i) = self.by_object.get(&key) {
            return Ok(i);
        }
        let m = build_medium(obj)?;
        let i = self.list.len() as u32;
        self.list.push(m);
        self.locs.push(obj.loc.clone());
        self.by_object.insert(key, i);
        Ok(i)
    }

    /// The medium `child` names, which must be a `<medium>` (`what` says where it is used).
    fn medium_of(&mut self, child: &Child, what: &str, owner: &Object) -> Result<u32> {
        if child.obj.kind != Kind::Medium {
            return Err(InputError::at(
                &child.loc,
                format!(
                    "\"{what}\" of {} must be a <medium>, found {}",
                    owner.describe(),
                    child.obj.describe()
                ),
            ));
        }
        self.index_of(&child.obj)
    }

    /// The media shape `obj` names on its sides (`interior`, `exterior`), marked as used.
    pub(crate) fn interface_of(&mut self, obj: &Object) -> Result<MediumInterface> {
        let side = |name: &str, media: &mut Media| -> Result<Option<u32>> {
            match obj.child(name) {
                Some(c) => Ok(Some(media.medium_of(c, name, obj)?)),
                None => Ok(None),
            }
        };
        let interior = side("interior", self)?;
        let exterior = side("exterior", self)?;
        // A medium nested without a side's name is a mistake Mitsuba also refuses.
        if let Some(c) = obj
            .children_of(Kind::Medium)
            .find(|c| !matches!(c.name.as_deref(), Some("interior" | "exterior")))
        {
            return Err(InputError::at(
                &c.loc,
                format!(
                    "a <medium> in {} needs name=\"interior\" or name=\"exterior\"",
                    obj.describe()
                ),
            ));
        }
        Ok(MediumInterface { interior, exterior })
    }

    /// The medium sensor `obj` sits in (its one nested or referenced `<medium>`), marked used.
    pub(crate) fn sensor_medium(&mut self, obj: &Object) -> Result<Option<u32>> {
        let mut found = None;
        for c in obj.children_of(Kind::Medium) {
            if found.is_some() {
                return Err(InputError::at(
                    &c.loc,
                    format!("{} names more than one medium", obj.describe()),
                ));
            }
            c.mark_used();
            found = Some(self.index_of(&c.obj)?);
        }
        Ok(found)
    }
}

//! Object ids: declaring them, `<ref>` to a declared object and `<alias>` for another id.

use std::rc::Rc;

use roxmltree::Node;

use super::attrs::Attrs;
use super::building::Building;
use super::object::{Child, Object};
use super::parse::{no_content, Parser, Result};
use super::source::Source;
use crate::error::{InputError, Loc};

impl Parser {
    /// Fails when `id` is already declared (or being declared).
    pub(super) fn check_new_id(&self, id: &str, loc: &Loc) -> Result<()> {
        let first = self
            .ids
            .get(id)
            .map(|(_, l)| l)
            .or_else(|| self.open_ids.get(id));
        match first {
            Some(first) => Err(InputError::at(
                loc,
                format!("duplicate id \"{id}\" (first declared at {first})"),
            )),
            None => Ok(()),
        }
    }

    /// The object declared with `id`.
    fn resolve(&self, id: &str, loc: &Loc) -> Result<Rc<Object>> {
        if let Some((obj, _)) = self.ids.get(id) {
            return Ok(obj.clone());
        }
        let msg = if self.open_ids.contains_key(id) {
            format!("id \"{id}\" refers to an object that contains this reference")
        } else {
            format!("unknown id \"{id}\" (objects must be declared before they are referenced)")
        };
        Err(InputError::at(loc, msg))
    }

    /// Reads a `<ref>` element: the referenced object becomes a child of `b`.
    pub(super) fn parse_ref(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        attrs: &Attrs,
        b: &mut Building,
    ) -> Result<()> {
        no_content(src, node)?;
        attrs.allow(&["id", "name"])?;
        let id = attrs.require("id")?;
        let obj = self.resolve(&id.value, &attrs.loc)?;
        obj.mark_referenced();
        let name = match attrs.get("name") {
            Some(a) if a.value.is_empty() => return Err(a.error(&attrs.tag, "must not be empty")),
            Some(a) => Some(b.param_name(&a.value)),
            None => None,
        };
        b.add_child(Child::new(name, obj, attrs.loc.clone(), true))
    }

    /// Reads an `<alias>` element: the object declared as `id` also becomes known `as` another id.
    pub(super) fn parse_alias(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        attrs: &Attrs,
    ) -> Result<()> {
        no_content(src, node)?;
        attrs.allow(&["id", "as"])?;
        let id = attrs.require("id")?;
        let new = attrs.require("as")?;
        let obj = self.resolve(&id.value, &id.loc)?;
        if new.value.is_empty() {
            return Err(new.error(&attrs.tag, "must not be empty"));
        }
        self.check_new_id(&new.value, &new.loc)?;
        self.ids.insert(new.value.clone(), (obj, attrs.loc.clone()));
        Ok(())
    }
}

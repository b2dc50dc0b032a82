//! Object ids: declaring them, `<ref>` to a declared object and `<alias>` for another id.

use roxmltree::Node;

use super::attrs::Attrs;
use super::building::Building;
use super::draft::{DraftChild, Target};
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

    /// What a `<ref>` to `id` points to: the object declared with it, or the id itself when
    /// it is not declared yet (it may be declared later; resolved when the load ends).
    fn ref_target(&self, id: &str, loc: &Loc) -> Result<Target> {
        if self.open_ids.contains_key(id) {
            return Err(InputError::at(
                loc,
                format!("id \"{id}\" refers to an object that contains this reference"),
            ));
        }
        Ok(match self.ids.get(id) {
            Some((at, _)) => Target::Node(*at),
            None => Target::Id(id.to_string()),
        })
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
        if id.value.is_empty() {
            return Err(id.error(&attrs.tag, "must not be empty"));
        }
        let target = self.ref_target(&id.value, &attrs.loc)?;
        let name = match attrs.get("name") {
            Some(a) if a.value.is_empty() => return Err(a.error(&attrs.tag, "must not be empty")),
            Some(a) => Some(b.param_name(&a.value)),
            None => None,
        };
        b.add_child(DraftChild {
            name,
            target,
            loc: attrs.loc.clone(),
            is_ref: true,
        })
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
        let Some(&(at, _)) = self.ids.get(&id.value) else {
            return Err(id.error(
                &attrs.tag,
                &format!(
                    "unknown id \"{}\" (an alias needs its object declared before it)",
                    id.value
                ),
            ));
        };
        if new.value.is_empty() {
            return Err(new.error(&attrs.tag, "must not be empty"));
        }
        self.check_new_id(&new.value, &new.loc)?;
        self.ids.insert(new.value.clone(), (at, attrs.loc.clone()));
        Ok(())
    }
}

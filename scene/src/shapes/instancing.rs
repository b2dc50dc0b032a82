//! The `shapegroup` and `instance` shapes (Mitsuba 3's instancing): a shape group holds shapes
//! that are drawn only through instances, each placing the group with its own `to_world`. The
//! group's shapes are built once, in object space, under their own hierarchy in the core
//! (`core/src/accel/level.rs`); an instance costs a transform and a top-level primitive.
//!
//! As in Mitsuba 3: a group holds only shapes (no nested groups or instances, no emitters); an
//! instance refers to exactly one group, by `<ref>`. A group that no instance uses draws nothing.
use super::{Geometry, ShapePlugin, TO_WORLD};
use crate::error::InputError;
use crate::plugin::Plugin;
use crate::util::Result;
use crate::xml::{Kind, Object};
use std::collections::HashMap;
use tessera_core::geometry::Instance;

/// `shapegroup`.
pub(crate) const SHAPEGROUP: ShapePlugin = Plugin {
    name: "shapegroup",
    aliases: &[],
    doc: "A group of shapes drawn only through `instance`s, stored once however many instances \
          place it. Its shapes may not carry emitters, and groups do not nest (as in Mitsuba 3).",
    params: &[],
    nested: "`<shape>`s",
    build: |_| Ok(Geometry::none()),
};

/// `instance`.
pub(crate) const INSTANCE: ShapePlugin = Plugin {
    name: "instance",
    aliases: &[],
    doc: "A copy of a `shapegroup` placed by to_world (any invertible affine transform; normals \
          follow its inverse transpose).",
    params: &[TO_WORLD],
    nested: "one `<ref>` to a `shapegroup`",
    build: |obj| {
        TO_WORLD.read_transform(obj)?;
        Ok(Geometry::none())
    },
};

/// The shape groups met so far, by object (a group is built once, where it is first met: its
/// declaration or an instance's reference to it).
#[derive(Default)]
pub struct Groups {
    by_object: HashMap<*const Object, u32>,
    lists: Vec<Vec<u32>>,
}

/// Builds one member shape of a group and returns the indices of the shapes it added.
pub(crate) type AddShape<'a> = dyn FnMut(&Object) -> Result<Vec<u32>> + 'a;

impl Groups {
    /// The index of group `obj`, building its member shapes with `add` the first time.
    pub fn group_of(&mut self, obj: &Object, add: &mut AddShape<'_>) -> Result<u32> {
        if let Some(&g) = self.by_object.get(&(obj as *const Object)) {
            return Ok(g);
        }
        let mut members = Vec::new();
        for c in &obj.children {
            if c.obj.kind != Kind::Shape {
                return Err(InputError::at(
                    &c.loc,
                    format!(
                        "a shapegroup holds only shapes, found {} (Mitsuba 3 refuses it too)",
                        c.obj.describe()
                    ),
                ));
            }
            members.extend(add(&c.obj)?);
            c.mark_used();
        }
        SHAPEGROUP.check_unused(obj)?;
        let g = self.lists.len() as u32;
        self.lists.push(members);
        self.by_object.insert(obj as *const Object, g);
        Ok(g)
    }

    /// The instance `obj`: its group (built with `add` if not yet) and its transform.
    pub fn instance(&mut self, obj: &Object, add: &mut AddShape<'_>) -> Result<Instance> {
        let mut group = None;
        for c in &obj.children {
            if c.obj.kind != Kind::Shape || c.obj.plugin != SHAPEGROUP.name {
                return Err(InputError::at(
                    &c.loc,
                    format!(
                        "an instance refers only to a shapegroup, found {}",
                        c.obj.describe()
                    ),
                ));
            }
            if group.is_some() {
                return Err(InputError::at(
                    &c.loc,
                    "an instance refers to a single shapegroup, found a second",
                ));
            }
            group = Some(self.group_of(&c.obj, add)?);
            c.mark_used();
        }
        let group = group.ok_or_else(|| {
            obj.error("an instance needs a <ref id=\"...\"/> to a shapegroup, found none")
        })?;
        let to_world = TO_WORLD.read_transform(obj)?;
        INSTANCE.check_unused(obj)?;
        Ok(Instance { group, to_world })
    }

    /// Each group's member shapes, by group index.
    pub(crate) fn into_shape_lists(self) -> Vec<Vec<u32>> {
        self.lists
    }
}

//! Plugins as data: each plugin the loader knows is one [`Plugin`] value (its name, a paragraph
//! of meaning, its declared [`Param`]s and its builder), listed once in its family's table
//! (`materials::BSDFS`, ...). Looking a plugin up, listing the known names in an error, checking
//! for parameters nobody read and writing the reference all go through these tables.
#[cfg(test)]
pub(crate) mod check;
pub mod doc;
pub(crate) mod param;
mod read;

pub use param::{Default, Param, ParamType, Range};

use crate::error::InputError;
use crate::xml::Object;

/// One plugin of a family; `B` is the family's builder type.
pub struct Plugin<B: 'static> {
    /// Name in the scene file (`type="..."`).
    pub name: &'static str,
    /// Other names that build the same plugin (other dialects' names).
    pub aliases: &'static [&'static str],
    /// What it is, in a sentence or two (the reference's paragraph).
    pub doc: &'static str,
    /// Its parameters.
    pub params: &'static [Param],
    /// The nested objects it takes, in words (empty: none).
    pub nested: &'static str,
    /// Builds it from a parsed object.
    pub build: B,
}

/// What a plugin declares, without its builder: the part all families share, for what reads
/// every family alike (the reference, the check for parameters without effect).
#[derive(Clone, Copy, Debug)]
pub struct Declared {
    /// Name in the scene file.
    pub name: &'static str,
    /// Other names that build the same plugin.
    pub aliases: &'static [&'static str],
    /// What it is.
    pub doc: &'static str,
    /// Its parameters.
    pub params: &'static [Param],
    /// The nested objects it takes, in words (empty: none).
    pub nested: &'static str,
}

impl Declared {
    /// Whether `name` names this plugin.
    pub fn is(&self, name: &str) -> bool {
        self.name == name || self.aliases.contains(&name)
    }
}

impl<B> Plugin<B> {
    /// Whether `name` names this plugin.
    pub fn is(&self, name: &str) -> bool {
        self.declared().is(name)
    }

    /// Its declaration without the builder.
    pub fn declared(&self) -> Declared {
        Declared {
            name: self.name,
            aliases: self.aliases,
            doc: self.doc,
            params: self.params,
            nested: self.nested,
        }
    }

    /// Rejects the parameters of `obj` nobody read, naming this plugin's declared ones.
    pub fn check_unused(&self, obj: &Object) -> Result<(), InputError> {
        obj.check_unused().map_err(|mut e| {
            let names: Vec<&str> = self.params.iter().map(|p| p.name).collect();
            e.msg = if names.is_empty() {
                format!("{} (it takes no parameters)", e.msg)
            } else {
                format!("{} (its parameters: {})", e.msg, names.join(", "))
            };
            e
        })
    }
}

/// The plugin of `family` that `obj` names, or a located error listing the known names.
pub fn find<'a, B>(
    family: &'a [Plugin<B>],
    what: &str,
    obj: &Object,
) -> Result<&'a Plugin<B>, InputError> {
    family.iter().find(|p| p.is(&obj.plugin)).ok_or_else(|| {
        let kind = match crate::mitsuba_names::is_mitsuba_plugin(obj.kind, &obj.plugin) {
            true => "Mitsuba 3's",
            false => "unknown",
        };
        let not_yet = match kind {
            "unknown" => "",
            _ => ", which Tessera does not read yet",
        };
        obj.error(format!(
            "{kind} {what} \"{}\"{not_yet} (Tessera reads: {})",
            obj.plugin,
            names(family)
        ))
    })
}

/// The names of a family's plugins, comma-separated, in table order.
pub fn names<B>(family: &[Plugin<B>]) -> String {
    let v: Vec<&str> = family
        .iter()
        .flat_map(|p| std::iter::once(p.name).chain(p.aliases.iter().copied()))
        .collect();
    v.join(", ")
}

//! [`Building`]: an object whose element is being read, with duplicate parameter detection.

use std::collections::HashMap;

use super::dialect::param_name;
use super::draft::DraftChild;
use super::object::{Kind, Prop};
use crate::error::{InputError, Loc};

type Result<T> = std::result::Result<T, InputError>;

/// An object whose element is being read.
pub(super) struct Building {
    pub(super) kind: Kind,
    pub(super) plugin: String,
    pub(super) props: Vec<Prop>,
    pub(super) children: Vec<DraftChild>,
    /// Parameter names (properties and named children) seen so far, for duplicates.
    pub(super) names: HashMap<String, Loc>,
}

impl Building {
    pub(super) fn new(kind: Kind, plugin: String) -> Self {
        Building {
            kind,
            plugin,
            props: Vec::new(),
            children: Vec::new(),
            names: HashMap::new(),
        }
    }

    pub(super) fn describe(&self) -> String {
        if self.plugin.is_empty() {
            self.kind.tag().to_string()
        } else {
            format!("{} \"{}\"", self.kind, self.plugin)
        }
    }

    /// Normalizes a parameter name for this object.
    pub(super) fn param_name(&self, raw: &str) -> String {
        param_name(raw, self.kind, &self.plugin)
    }

    pub(super) fn claim_name(&mut self, name: &str, loc: &Loc) -> Result<()> {
        if let Some(first) = self.names.get(name) {
            return Err(InputError::at(
                loc,
                format!(
                    "parameter \"{name}\" of {} is specified twice (first at {first})",
                    self.describe()
                ),
            ));
        }
        self.names.insert(name.to_string(), loc.clone());
        Ok(())
    }

    pub(super) fn add_prop(&mut self, prop: Prop) -> Result<()> {
        self.claim_name(&prop.name, &prop.loc)?;
        self.props.push(prop);
        Ok(())
    }

    pub(super) fn add_child(&mut self, child: DraftChild) -> Result<()> {
        if let Some(n) = &child.name {
            self.claim_name(n, &child.loc)?;
        }
        self.children.push(child);
        Ok(())
    }
}

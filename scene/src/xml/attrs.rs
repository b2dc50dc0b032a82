//! The attributes of one element, after `$name` substitution, with their locations.
//!
//! Gives located errors for unknown, missing and malformed attributes.

use std::collections::HashMap;

use super::source::Source;
use super::subst::substitute;
use super::values;
use crate::error::{InputError, Loc};

type Result<T> = std::result::Result<T, InputError>;

/// One attribute: its name, its value after substitution, and where it is.
pub(crate) struct Attr {
    /// The attribute name.
    pub name: String,
    /// The value, with `$name` parameters replaced.
    pub value: String,
    /// Where the attribute starts.
    pub loc: Loc,
}

/// The attributes of an element.
pub(crate) struct Attrs {
    /// The element name as written in the file (for messages).
    pub tag: String,
    /// Where the element starts.
    pub loc: Loc,
    items: Vec<Attr>,
}

impl Attrs {
    /// Reads the attributes of `node`, substituting parameters.
    pub fn read(
        node: roxmltree::Node<'_, '_>,
        src: &Source<'_>,
        params: &HashMap<String, String>,
    ) -> Result<Attrs> {
        let tag = node.tag_name().name().to_string();
        let loc = src.loc(node.range().start);
        let mut items = Vec::new();
        for a in node.attributes() {
            let aloc = src.loc(a.range().start);
            let value = substitute(a.value(), params)
                .map_err(|m| InputError::at(&aloc, format!("in attribute \"{}\": {m}", a.name())))?
                .into_owned();
            items.push(Attr {
                name: a.name().to_string(),
                value,
                loc: aloc,
            });
        }
        Ok(Attrs { tag, loc, items })
    }

    /// Fails on the first attribute not in `allowed`.
    pub fn allow(&self, allowed: &[&str]) -> Result<()> {
        match self
            .items
            .iter()
            .find(|a| !allowed.contains(&a.name.as_str()))
        {
            None => Ok(()),
            Some(a) => {
                let list = allowed
                    .iter()
                    .map(|s| format!("\"{s}\""))
                    .collect::<Vec<_>>()
                    .join(", ");
                let hint = if allowed.is_empty() {
                    "it takes no attributes".to_string()
                } else {
                    format!("allowed: {list}")
                };
                Err(InputError::at(
                    &a.loc,
                    format!(
                        "unknown attribute \"{}\" on <{}> ({hint})",
                        a.name, self.tag
                    ),
                ))
            }
        }
    }

    /// The attribute called `name`.
    pub fn get(&self, name: &str) -> Option<&Attr> {
        self.items.iter().find(|a| a.name == name)
    }

    /// The attribute called `name`, or a located error saying it is missing.
    pub(crate) fn require(&self, name: &str) -> Result<&Attr> {
        self.get(name).ok_or_else(|| {
            self.error(format!(
                "<{}> is missing the \"{name}\" attribute",
                self.tag
            ))
        })
    }

    /// An error located at the element.
    pub fn error(&self, msg: impl Into<String>) -> InputError {
        InputError::at(&self.loc, msg)
    }

    /// Whether any attribute named in `names` is present.
    pub fn any(&self, names: &[&str]) -> bool {
        names.iter().any(|n| self.get(n).is_some())
    }
}

impl Attr {
    /// An error about this attribute's value.
    pub fn error(&self, tag: &str, msg: &str) -> InputError {
        InputError::at(
            &self.loc,
            format!("attribute \"{}\" of <{tag}>: {msg}", self.name),
        )
    }

    /// The value as a finite float.
    pub fn float(&self, tag: &str) -> Result<f64> {
        values::parse_float(&self.value).map_err(|m| self.error(tag, &m))
    }

    /// The value as an integer.
    pub fn int(&self, tag: &str) -> Result<i64> {
        values::parse_int(&self.value).map_err(|m| self.error(tag, &m))
    }

    /// The value as a boolean.
    pub fn boolean(&self, tag: &str) -> Result<bool> {
        values::parse_bool(&self.value).map_err(|m| self.error(tag, &m))
    }

    /// The value as a list of floats.
    pub fn floats(&self, tag: &str) -> Result<Vec<f64>> {
        values::parse_floats(&self.value).map_err(|m| self.error(tag, &m))
    }

    /// The value as three floats (or one, repeated, when `allow_one`).
    pub fn vec3(&self, tag: &str, allow_one: bool) -> Result<[f64; 3]> {
        values::parse_vec3(&self.value, allow_one).map_err(|m| self.error(tag, &m))
    }
}

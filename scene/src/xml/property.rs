//! Property elements (`<float>`, `<rgb>`, `<spectrum>`, `<point>`, `<transform>`, ...) to
//! [`Prop`]s.

use std::path::Path;

use glam::DMat4;
use roxmltree::Node;

use super::attrs::Attrs;
use super::building::Building;
use super::object::{Prop, Value};
use super::parse::{check_text, no_content, Parser, Result, MAX_DEPTH};
use super::search::lookup;
use super::source::{read_text, Source};
use super::spectrum::{list_to_rgb, parse_file, parse_pairs, uniform_to_rgb, SpectrumUse};
use super::transform;
use crate::error::InputError;

impl Parser {
    /// Reads a property element.
    pub(super) fn parse_property(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        tag: &str,
        a: &Attrs,
        b: &Building,
        depth: usize,
    ) -> Result<Prop> {
        let name = a.require("name")?;
        if name.value.is_empty() {
            return Err(name.error(&a.tag, "must not be empty"));
        }
        let value = match tag {
            "transform" => {
                a.allow(&["name"])?;
                Value::Transform(self.parse_transform(src, node, depth)?)
            }
            _ => {
                no_content(src, node)?;
                if tag == "spectrum" {
                    let how = SpectrumUse::of(b.kind, &b.plugin, &b.param_name(&name.value));
                    self.spectrum_value(src, a, how)?
                } else {
                    self.simple_value(tag, a)?
                }
            }
        };
        Ok(Prop::new(b.param_name(&name.value), value, a.loc.clone()))
    }

    /// The value of a property element other than `<transform>`.
    fn simple_value(&self, tag: &str, a: &Attrs) -> Result<Value> {
        let t = a.tag.as_str();
        Ok(match tag {
            "float" | "integer" | "boolean" | "string" | "rgb" => {
                a.allow(&["name", "value"])?;
                let v = a.require("value")?;
                match tag {
                    "float" => Value::Float(v.float(t)?),
                    "integer" => Value::Integer(v.int(t)?),
                    "boolean" => Value::Boolean(v.boolean(t)?),
                    "string" => Value::String(v.value.clone()),
                    _ => Value::Rgb(v.vec3(t, true)?),
                }
            }
            "point" | "vector" => {
                a.allow(&["name", "value", "x", "y", "z"])?;
                let v = transform::xyz(a, &["value"], 0.0, true)?
                    .ok_or_else(|| {
                        a.error(format!(
                            "<{t}> needs a \"value\" or \"x\"/\"y\"/\"z\" attributes"
                        ))
                    })?
                    .to_array();
                if tag == "point" {
                    Value::Point(v)
                } else {
                    Value::Vector(v)
                }
            }
            _ => unreachable!("not a simple property tag: {tag}"),
        })
    }

    /// The value of a `<spectrum>`: one value (grey, or for emitted light Mitsuba's flat
    /// spectrum colour), a wavelength:value list, or a file of them, converted to RGB.
    fn spectrum_value(&mut self, src: &Source<'_>, a: &Attrs, how: SpectrumUse) -> Result<Value> {
        let t = a.tag.as_str();
        a.allow(&["name", "value", "filename"])?;
        let (w, v) = match (a.get("value"), a.get("filename")) {
            (Some(_), Some(f)) => {
                return Err(f.error(t, "give either \"value\" or \"filename\", not both"))
            }
            (Some(v), None) => {
                let items: Vec<&str> = super::values::split_list(&v.value).collect();
                if let [one] = items.as_slice() {
                    if !one.contains(':') {
                        let x = v.float(t)?;
                        return Ok(match how {
                            SpectrumUse::Emitted => Value::Rgb(uniform_to_rgb(x, how)),
                            _ => Value::Float(x),
                        });
                    }
                }
                parse_pairs(&v.value).map_err(|m| v.error(t, &m))?
            }
            (None, Some(f)) => {
                if f.value.is_empty() {
                    return Err(f.error(t, "must not be empty"));
                }
                let name = Path::new(&f.value);
                let path = lookup(&self.resolver, name)
                    .or_else(|| lookup(std::slice::from_ref(&src.dir), name))
                    .unwrap_or_else(|| src.dir.join(name));
                let text = read_text(&path)
                    .map_err(|m| f.error(t, &format!("\"{}\": {m}", path.display())))?;
                parse_file(&text)
                    .map_err(|m| f.error(t, &format!("in \"{}\": {m}", path.display())))?
            }
            (None, None) => {
                return Err(a.error(format!("<{t}> needs a \"value\" or a \"filename\"")))
            }
        };
        let (rgb, unclamped) = list_to_rgb(&w, &v, how);
        if let Some(c) = unclamped {
            self.warnings.push(format!(
                "{}: the spectrum's colour [{:.4}, {:.4}, {:.4}] is out of gamut; clamped to \
                 [{:.4}, {:.4}, {:.4}] as Mitsuba does",
                a.loc, c[0], c[1], c[2], rgb[0], rgb[1], rgb[2]
            ));
        }
        Ok(Value::Rgb(rgb))
    }

    /// Composes the operations inside a `<transform>` element (`M = op * M`).
    fn parse_transform(
        &mut self,
        src: &Source<'_>,
        node: Node<'_, '_>,
        depth: usize,
    ) -> Result<DMat4> {
        let mut m = DMat4::IDENTITY;
        for ch in node.children() {
            if !ch.is_element() {
                check_text(src, node, ch)?;
                continue;
            }
            let loc = src.loc(ch.range().start);
            if depth + 1 > MAX_DEPTH {
                return Err(InputError::at(
                    &loc,
                    format!("elements are nested deeper than {MAX_DEPTH} levels"),
                ));
            }
            let tag = ch.tag_name().name();
            if !transform::is_op(tag) {
                return Err(InputError::at(
                    &loc,
                    format!(
                        "<{tag}> is not allowed inside <transform> (expected translate, scale, rotate, matrix or lookat)"
                    ),
                ));
            }
            let a = Attrs::read(ch, src, &self.params)?;
            no_content(src, ch)?;
            m = transform::op_matrix(&a, &mut self.warnings)? * m;
        }
        Ok(m)
    }
}

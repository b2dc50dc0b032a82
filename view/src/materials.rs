//! The BSDFs of a scene file as the view lists and edits them: every `<bsdf>` element of the
//! file (nested ones too, in document order), with the parameters a colour picker or a number
//! input can set (colours, textures and floats the plugin declares), their current values and
//! the ranges the loader accepts (from the plugin's declarations in `tessera_scene::plugin`).
use crate::xml_text::named_child;
use roxmltree::{Document, Node};
use serde::Serialize;
use tessera_scene::plugin::{Default, Param, ParamType, Range};

/// An editable parameter's value.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Value {
    /// A number.
    Float(f64),
    /// A linear RGB colour.
    Rgb([f64; 3]),
}

/// One `<bsdf>` element of the file.
#[derive(Clone, Debug, Serialize)]
pub struct BsdfEntry {
    /// Its position among the file's `<bsdf>` elements (document order).
    pub index: usize,
    /// Its `id`, if it has one.
    pub id: Option<String>,
    /// Its plugin (`type`).
    pub r#type: String,
    /// Where it is: the ids or types of the elements around it (`shape floor > twosided`).
    pub path: String,
    /// What can be edited.
    pub params: Vec<ParamEntry>,
}

/// One editable parameter of a BSDF.
#[derive(Clone, Debug, Serialize)]
pub struct ParamEntry {
    /// Its name in the file.
    pub name: String,
    /// `"rgb"` or `"float"`.
    pub kind: &'static str,
    /// Its value in the file, or the default (`None`: a texture, a reference, a spectrum or a
    /// `$default` the view cannot show as a number; editing replaces it).
    pub value: Option<Value>,
    /// Where the value comes from: `"file"`, `"default"` or what the file gives instead.
    pub source: String,
    /// Smallest accepted value (per channel for colours), if bounded.
    pub min: Option<f64>,
    /// Whether `min` itself is refused.
    pub min_open: bool,
    /// Largest accepted value, if bounded.
    pub max: Option<f64>,
    /// Whether `max` itself is refused.
    pub max_open: bool,
    /// The declaration's one line of meaning.
    pub doc: &'static str,
}

/// Whether a declared parameter is one the view edits, and as what.
pub fn kind_of(p: &Param) -> Option<&'static str> {
    if p.ignored {
        return None;
    }
    match (p.ty, p.range) {
        // A texture whose default is a number is a scalar one (a roughness): a number input.
        (ParamType::Texture, _) if !matches!(p.default, Default::Rgb(_)) => Some("float"),
        (ParamType::Rgb | ParamType::Texture, _) => Some("rgb"),
        (ParamType::Float | ParamType::Ior, Range::OneOf(_) | Range::OneOfAnyCase(_)) => None,
        (ParamType::Float | ParamType::Ior, _) => Some("float"),
        _ => None,
    }
}

/// `(min, min_open, max, max_open)` of a numeric range.
fn bounds(r: &Range) -> (Option<f64>, bool, Option<f64>, bool) {
    match *r {
        Range::NonNegative => (Some(0.0), false, None, false),
        Range::Positive => (Some(0.0), true, None, false),
        Range::Unit => (Some(0.0), false, Some(1.0), false),
        Range::Between {
            lo,
            lo_closed,
            hi,
            hi_closed,
        } => (
            lo.is_finite().then_some(lo),
            !lo_closed,
            hi.is_finite().then_some(hi),
            !hi_closed,
        ),
        _ => (None, false, None, false),
    }
}

/// Every `<bsdf>` element of the document, in document order.
pub fn bsdf_nodes<'a, 'i>(doc: &'a Document<'i>) -> Vec<Node<'a, 'i>> {
    doc.descendants()
        .filter(|n| n.is_element() && n.tag_name().name() == "bsdf")
        .collect()
}

/// The BSDF element that `key` names: an index (`3`) or an id (`"floor"`).
pub fn find<'a, 'i>(doc: &'a Document<'i>, key: &Key) -> Result<(usize, Node<'a, 'i>), String> {
    let nodes = bsdf_nodes(doc);
    match key {
        Key::Index(i) => nodes
            .get(*i)
            .map(|n| (*i, *n))
            .ok_or_else(|| format!("no BSDF has index {i} (the file has {})", nodes.len())),
        Key::Id(id) => nodes
            .iter()
            .enumerate()
            .find(|(_, n)| n.attribute("id") == Some(id.as_str()))
            .map(|(i, n)| (i, *n))
            .ok_or_else(|| format!("no BSDF has id \"{id}\"")),
    }
}

/// How a request names a BSDF.
#[derive(Clone, Debug, PartialEq)]
pub enum Key {
    /// Position among the file's `<bsdf>` elements.
    Index(usize),
    /// Its `id`.
    Id(String),
}

/// The entries of the file's BSDFs.
pub fn list(doc: &Document) -> Vec<BsdfEntry> {
    bsdf_nodes(doc)
        .iter()
        .enumerate()
        .map(|(index, n)| entry(index, *n))
        .collect()
}

fn entry(index: usize, n: Node) -> BsdfEntry {
    let ty = n.attribute("type").unwrap_or("").to_string();
    let params = tessera_scene::plugin_declaration("bsdf", &ty)
        .map(|d| d.params)
        .unwrap_or(&[]);
    let params = params
        .iter()
        .filter_map(|p| {
            let kind = kind_of(p)?;
            let (value, source) = current(n, p, kind);
            let (min, min_open, max, max_open) = bounds(&p.range);
            Some(ParamEntry {
                name: p.name.to_string(),
                kind,
                value,
                source,
                min,
                min_open,
                max,
                max_open,
                doc: p.doc,
            })
        })
        .collect();
    let path: Vec<String> = n
        .ancestors()
        .skip(1)
        .filter(|a| a.is_element() && a.tag_name().name() != "scene")
        .map(|a| {
            let what = a.attribute("id").or(a.attribute("type")).unwrap_or("");
            format!("{} {what}", a.tag_name().name())
        })
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    BsdfEntry {
        index,
        id: n.attribute("id").map(str::to_string),
        r#type: ty,
        path: path.join(" > "),
        params,
    }
}

/// A parameter's value as the file gives it (or its default).
fn current(n: Node, p: &Param, kind: &str) -> (Option<Value>, String) {
    let Some(c) = named_child(n, p.name) else {
        let v = match (p.default, kind) {
            (Default::Rgb(c), "rgb") => Some(Value::Rgb(c)),
            (Default::Float(f), "rgb") => Some(Value::Rgb([f; 3])),
            (Default::Float(f), _) => Some(Value::Float(f)),
            _ => None,
        };
        return (v, "default".into());
    };
    let tag = c.tag_name().name();
    let numbers: Option<Vec<f64>> = c.attribute("value").and_then(|s| {
        s.split(|ch: char| ch == ',' || ch.is_whitespace())
            .filter(|t| !t.is_empty())
            .map(|t| t.parse::<f64>().ok())
            .collect()
    });
    let v = match (tag, numbers.as_deref(), kind) {
        ("rgb" | "float" | "spectrum" | "integer", Some(&[x]), "rgb") => Some(Value::Rgb([x; 3])),
        ("rgb", Some(&[r, g, b]), "rgb") => Some(Value::Rgb([r, g, b])),
        ("float" | "integer" | "rgb" | "spectrum", Some(&[x]), "float") => Some(Value::Float(x)),
        _ => None,
    };
    match v {
        Some(v) => (Some(v), "file".into()),
        None => {
            let what = c
                .attribute("type")
                .map_or(String::new(), |t| format!(" {t}"));
            (None, format!("<{tag}{what}>"))
        }
    }
}

/// Checks `value` against parameter `name` of the BSDF element `n` (its plugin's declaration);
/// returns the element that will stand for it in the file.
pub fn element_for(n: Node, name: &str, value: &Value) -> Result<String, String> {
    let ty = n.attribute("type").unwrap_or("");
    let decl = tessera_scene::plugin_declaration("bsdf", ty)
        .ok_or_else(|| format!("BSDF type \"{ty}\" is not one the view can edit"))?;
    let p = decl.params.iter().find(|p| p.name == name).ok_or_else(|| {
        let names: Vec<&str> = decl
            .params
            .iter()
            .filter(|p| kind_of(p).is_some())
            .map(|p| p.name)
            .collect();
        format!(
            "BSDF \"{ty}\" has no editable parameter \"{name}\" (it has: {})",
            names.join(", ")
        )
    })?;
    let kind = kind_of(p).ok_or_else(|| format!("parameter \"{name}\" is not editable here"))?;
    let n = crate::xml_text::number;
    let channels: Vec<f64> = match (kind, value) {
        ("rgb", Value::Rgb(c)) => c.to_vec(),
        ("rgb", Value::Float(x)) => vec![*x; 3],
        (_, Value::Float(x)) => vec![*x],
        (_, Value::Rgb(_)) => return Err(format!("parameter \"{name}\" takes a number")),
    };
    if let Some(bad) = channels.iter().find(|c| !p.range.contains(**c)) {
        return Err(format!(
            "{ty}'s \"{name}\" must be {}, found {bad}",
            p.range.describe()
        ));
    }
    Ok(match kind {
        "rgb" => format!(
            "<rgb name=\"{name}\" value=\"{}, {}, {}\"/>",
            n(channels[0]),
            n(channels[1]),
            n(channels[2])
        ),
        _ => format!("<float name=\"{name}\" value=\"{}\"/>", n(channels[0])),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_get_pickers_and_scalar_textures_numbers() {
        let text = r#"<scene version="3.0.0">
            <bsdf type="roughconductor" id="metal"><float name="alpha" value="0.25"/></bsdf>
            <bsdf type="diffuse"><texture type="bitmap" name="reflectance"/></bsdf></scene>"#;
        let doc = crate::xml_text::parse(text).unwrap();
        let list = list(&doc);
        let p = |i: usize, n: &str| list[i].params.iter().find(|p| p.name == n).unwrap().clone();
        let alpha = p(0, "alpha");
        assert_eq!(
            (alpha.kind, alpha.value),
            ("float", Some(Value::Float(0.25)))
        );
        assert_eq!((alpha.min, alpha.min_open), (Some(0.0), true));
        let eta = p(0, "eta");
        assert_eq!((eta.kind, eta.source.as_str()), ("rgb", "default"));
        let refl = p(1, "reflectance");
        assert_eq!(
            (refl.value, refl.source.as_str()),
            (None, "<texture bitmap>")
        );
        let (_, metal) = find(&doc, &Key::Id("metal".into())).unwrap();
        assert!(
            element_for(metal, "alpha", &Value::Float(0.0)).is_err(),
            "alpha > 0"
        );
        assert_eq!(
            element_for(metal, "alpha", &Value::Float(0.5)).unwrap(),
            r#"<float name="alpha" value="0.5"/>"#
        );
        assert!(element_for(metal, "alpha", &Value::Rgb([0.5; 3])).is_err());
    }
}

//! Rewrites of a scene file's text at the byte ranges `roxmltree` reports: replace an element,
//! insert a child, set an attribute's value. Every edit the view makes is one of these, so the
//! edited scene stays the user's file (comments, layout, `<default>`s and all) with only the
//! edited parts changed, and `GET /api/scene.xml` can hand it out as it is.
use roxmltree::{Document, Node};
use std::ops::Range;

/// Parses scene text, with the parser's message on failure.
pub fn parse(text: &str) -> Result<Document<'_>, String> {
    // DTDs are allowed (Mitsuba files rarely have them, but some exporters write one).
    let opts = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    Document::parse_with_options(text, opts).map_err(|e| format!("the scene text: {e}"))
}

/// `text` with `range` replaced by `with`.
pub fn splice(text: &str, range: Range<usize>, with: &str) -> String {
    let mut s = String::with_capacity(text.len() + with.len());
    s.push_str(&text[..range.start]);
    s.push_str(with);
    s.push_str(&text[range.end..]);
    s
}

/// `text` with `child` (an element's XML) added as the first child of `parent`.
pub fn insert_first_child(text: &str, parent: Node, child: &str) -> String {
    let r = parent.range();
    if let Some(first) = parent.first_child() {
        let at = first.range().start;
        return splice(text, at..at, &format!("\n    {child}"));
    }
    let own = &text[r.clone()];
    if own.ends_with("/>") {
        // `<tag .../>` becomes `<tag ...>child</tag>`.
        let tag = parent.tag_name().name();
        return splice(text, r.end - 2..r.end, &format!(">\n    {child}\n</{tag}>"));
    }
    // `<tag ...></tag>`: before the end tag.
    let at = r.start + own.rfind("</").unwrap_or(own.len());
    splice(text, at..at, child)
}

/// `text` with the value of attribute `name` of `node` set to `value` (escaped); the attribute
/// is added when missing.
pub fn set_attribute(text: &str, node: Node, name: &str, value: &str) -> String {
    let value = escape(value);
    match node.attributes().find(|a| a.name() == name) {
        Some(a) => splice(text, a.range_value(), &value),
        None => {
            // After the tag name.
            let at = node.range().start + 1 + node.tag_name().name().len();
            splice(text, at..at, &format!(" {name}=\"{value}\""))
        }
    }
}

/// The element child of `node` whose `name` attribute is `name` (a plugin parameter).
pub fn named_child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    node.children()
        .filter(Node::is_element)
        .find(|c| c.attribute("name") == Some(name))
}

/// The element children of `node` with tag `tag`.
pub fn children_tagged<'a, 'i>(
    node: Node<'a, 'i>,
    tag: &'a str,
) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == tag)
}

/// A value escaped for an attribute in double quotes.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A number as a scene file writes it: the shortest text that reads back as the same `f64`.
pub fn number(v: f64) -> String {
    format!("{v}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_child_goes_into_a_self_closing_element_and_an_attribute_is_set_in_place() {
        let text = r#"<scene version="3.0.0"><bsdf type="diffuse"/></scene>"#;
        let doc = parse(text).unwrap();
        let bsdf = doc.root_element().first_child().unwrap();
        let t = insert_first_child(text, bsdf, r#"<float name="x" value="1"/>"#);
        assert!(t.contains("<bsdf type=\"diffuse\">\n    <float name=\"x\" value=\"1\"/>\n</bsdf>"));
        let doc = parse(&t).unwrap();
        let bsdf = doc.root_element().first_child().unwrap();
        let t2 = set_attribute(&t, bsdf, "type", "conductor");
        assert!(t2.contains("<bsdf type=\"conductor\">"), "{t2}");
        let doc = parse(&t2).unwrap();
        let bsdf = doc.root_element().first_child().unwrap();
        assert!(set_attribute(&t2, bsdf, "id", "a\"b").contains("<bsdf id=\"a&quot;b\" type"));
    }
}

//! The reference text of a plugin, written from its declaration: a heading, its paragraph, and a
//! table of its parameters (type, default, range, meaning). The committed reference and
//! `tessera plugins` print this, so neither can drift from what the loader reads.
use super::Declared;
use std::fmt::Write;

/// The Markdown reference of one plugin of family `family` (`"bsdf"`, ...).
pub(crate) fn plugin_markdown(family: &str, p: &Declared) -> String {
    let mut s = format!("### `{family}` `{}`", p.name);
    if !p.aliases.is_empty() {
        let a: Vec<String> = p.aliases.iter().map(|a| format!("`{a}`")).collect();
        let _ = write!(s, " (also {})", a.join(", "));
    }
    let _ = write!(s, "\n\n{}\n", p.doc);
    if !p.nested.is_empty() {
        let _ = write!(s, "\nNested: {}.\n", p.nested);
    }
    if p.params.is_empty() {
        s.push_str("\nNo parameters.\n");
        return s;
    }
    s.push_str("\n| parameter | type | default | range | meaning |\n|---|---|---|---|---|\n");
    // A `|` inside a cell would end it.
    let cell = |t: String| t.replace('|', "\\|");
    for q in p.params {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} |",
            q.name,
            q.ty.describe(),
            cell(q.default.to_string()),
            cell(q.describe_range()),
            cell(q.doc.to_string())
        );
    }
    s
}

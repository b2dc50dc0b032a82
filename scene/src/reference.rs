//! The plugin reference, written from the loader's tables: every plugin of every family with
//! its parameters. `docs/reference/plugins.md` is this text (a test keeps it so) and
//! `tessera plugins [NAME]` prints it.
use crate::families::families;
use crate::plugin::doc::plugin_markdown;

/// Every family's section, or only the entries named `only` (without section titles).
fn sections(only: Option<&str>) -> Vec<String> {
    let mut out = Vec::new();
    for f in families() {
        let tag = f.kind.tag();
        let entries: Vec<String> = f
            .plugins
            .iter()
            .filter(|p| only.is_none_or(|n| p.is(n)))
            .map(|p| plugin_markdown(tag, p))
            .collect();
        if entries.is_empty() {
            continue;
        }
        if only.is_none() {
            out.push(format!("## {} (`<{tag}>`)\n", f.title));
        }
        out.extend(entries);
    }
    out
}

/// The whole reference, in Markdown.
pub fn reference() -> String {
    let mut s = String::from(
        "# Plugin reference\n\nEvery plugin a scene file can name with `type=\"...\"`, with its \
         parameters, as the loader declares them (this file is generated: `tessera plugins > \
         docs/reference/plugins.md`). Names, defaults and meanings follow Mitsuba 3 unless a \
         paragraph says otherwise. A parameter a plugin does not declare is an error naming \
         the ones it does.\n\n",
    );
    s.push_str(&sections(None).join("\n"));
    s.push_str(
        "\n## Mitsuba 3 plugins Tessera does not read\n\nMitsuba 3.9.1's plugins of the \
         families above that the loader has no entry for; a scene file naming one is refused \
         with a located error that says so.\n\n",
    );
    for f in families() {
        let missing = f.not_read();
        if !missing.is_empty() {
            let list: Vec<String> = missing.iter().map(|n| format!("`{n}`")).collect();
            s.push_str(&format!(
                "- {} (`<{}>`): {}\n",
                f.title,
                f.kind.tag(),
                list.join(", ")
            ));
        }
    }
    s
}

/// The reference of the plugins called `name` (in any family), or `None` if there is none.
pub fn plugin_reference(name: &str) -> Option<String> {
    let v = sections(Some(name));
    (!v.is_empty()).then(|| v.join("\n"))
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_committed_reference_is_what_the_loader_declares() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/reference/plugins.md");
        let committed = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            committed == super::reference(),
            "docs/reference/plugins.md differs from the loader's declarations; regenerate it: \
             cargo run --release --bin tessera -- plugins > docs/reference/plugins.md"
        );
    }

    #[test]
    fn one_plugin_is_looked_up_by_any_of_its_names() {
        let text = super::plugin_reference("roughplastic").expect("roughplastic is a plugin");
        assert!(
            text.contains("`alpha_u`") && text.contains("| `distribution` |"),
            "{text}"
        );
        let blend = super::plugin_reference("blend").expect("blend is an alias of blendbsdf");
        assert!(blend.starts_with("### `bsdf` `blendbsdf`"), "{blend}");
        assert!(super::plugin_reference("no_such_plugin").is_none());
    }
}

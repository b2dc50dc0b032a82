//! The plugin reference, written from the loader's tables: every plugin of every family with
//! its parameters. `docs/reference/plugins.md` is this text (a test keeps it so) and
//! `tessera plugins [NAME]` prints it.
use crate::plugin::doc::plugin_markdown;
use crate::plugin::Plugin;

/// One family's section, or the entries named `only` in it.
fn family<B>(
    out: &mut Vec<String>,
    tag: &str,
    title: &str,
    list: &[Plugin<B>],
    only: Option<&str>,
) {
    let entries: Vec<String> = list
        .iter()
        .filter(|p| only.is_none_or(|n| p.is(n)))
        .map(|p| plugin_markdown(tag, p))
        .collect();
    if entries.is_empty() {
        return;
    }
    if only.is_none() {
        out.push(format!("## {title} (`<{tag}>`)\n"));
    }
    out.extend(entries);
}

fn sections(only: Option<&str>) -> Vec<String> {
    let mut out = Vec::new();
    family(
        &mut out,
        "integrator",
        "Integrators",
        crate::integrator::INTEGRATORS,
        only,
    );
    family(
        &mut out,
        "sampler",
        "Samplers",
        crate::sampler::SAMPLERS,
        only,
    );
    family(&mut out, "sensor", "Sensors", crate::sensor::SENSORS, only);
    family(&mut out, "film", "Films", crate::sensor::FILMS, only);
    family(
        &mut out,
        "rfilter",
        "Reconstruction filters",
        crate::filter::FILTERS,
        only,
    );
    family(&mut out, "shape", "Shapes", crate::shapes::SHAPES, only);
    family(&mut out, "bsdf", "BSDFs", crate::materials::BSDFS, only);
    family(
        &mut out,
        "texture",
        "Textures",
        crate::materials::texture::TEXTURES,
        only,
    );
    family(
        &mut out,
        "emitter",
        "Emitters",
        crate::emitters::EMITTERS,
        only,
    );
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

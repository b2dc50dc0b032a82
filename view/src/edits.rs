//! The edits made in the view, kept as data and applied as rewrites of the scene file's text:
//! `-D` defines baked into the `<default>`s, the integrator's type and `max_depth`, the
//! sampler's type, BSDF parameters, and the camera as a `<lookat>` in the sensor's `to_world`.
//! The text they give is what the view renders (reloaded through the ordinary loader) and what
//! `GET /api/scene.xml` hands out, so `tessera render` of that file is the view's image.
//!
//! Edits are applied to the file's original text every time, in a fixed order (integrator,
//! sampler, materials, camera), so undoing one (the camera's reset) needs no inverse.
use crate::camera::Pose;
use crate::materials::{self, Key, Value};
use crate::xml_text::{
    children_tagged, insert_first_child, named_child, parse, set_attribute, splice,
};
use roxmltree::{Document, Node};

/// Everything edited so far.
#[derive(Clone, Debug, Default)]
pub struct Edits {
    /// The camera's pose (`None`: the file's).
    pub camera: Option<Pose>,
    /// BSDF parameters: (BSDF index, parameter, the element written for it), latest last.
    pub materials: Vec<(usize, String, String)>,
    /// The integrator's type (`None`: the file's).
    pub integrator: Option<String>,
    /// The integrator's `max_depth` (-1: unbounded; `None`: the file's).
    pub max_depth: Option<i64>,
    /// The sampler's type (`None`: the file's).
    pub sampler: Option<String>,
}

/// Integrators the view offers: those that render a whole image from the scene alone (not the
/// wrappers `moment` and `aov`, nor `simple`, which needs a point light only its file gives).
pub fn integrator_choices() -> Vec<&'static str> {
    tessera_scene::plugin_names("integrator")
        .into_iter()
        .filter(|n| !matches!(*n, "moment" | "aov" | "simple"))
        .collect()
}

/// Why edits cannot be made to this file, if they cannot: the view rewrites Mitsuba 3
/// vocabulary (`<sensor>`, `to_world`, `<rgb>`), so Nori files and Mitsuba 0.x files are shown
/// as they are.
pub fn not_editable(doc: &Document) -> Option<String> {
    let root = doc.root_element();
    let major = root
        .attribute("version")
        .and_then(|v| v.split('.').next())
        .and_then(|m| m.trim().parse::<u32>().ok());
    match (root.tag_name().name(), major) {
        ("scene", Some(m)) if m >= 2 => None,
        _ => Some(
            "edits need a Mitsuba 3 scene file (<scene version=\"3.0.0\">); this one is shown \
             as it is"
                .into(),
        ),
    }
}

/// `text` with the `-D name=value` defines written into its `<default>`s (a define without a
/// `<default>` becomes one), so that the text alone renders as the file did with them.
pub fn bake_defines(text: &str, defines: &[(String, String)]) -> Result<String, String> {
    let mut text = text.to_string();
    for (name, value) in defines {
        let doc = parse(&text)?;
        let root = doc.root_element();
        let found = children_tagged(root, "default").find(|d| d.attribute("name") == Some(name));
        let t = match found {
            Some(d) => set_attribute(&text, d, "value", value),
            None => insert_first_child(
                &text,
                root,
                &format!(
                    "<default name=\"{}\" value=\"{}\"/>",
                    crate::xml_text::escape(name),
                    crate::xml_text::escape(value)
                ),
            ),
        };
        text = t;
    }
    Ok(text)
}

/// The sensor element.
fn sensor<'a, 'i>(doc: &'a Document<'i>) -> Result<Node<'a, 'i>, String> {
    children_tagged(doc.root_element(), "sensor")
        .next()
        .ok_or_else(|| "the scene has no <sensor> to edit".to_string())
}

impl Edits {
    /// Sets a BSDF parameter (checked against the plugin's declaration), replacing an earlier
    /// edit of the same parameter. `text` is the base text (BSDF indices are the same in every
    /// edited text: edits never add or remove a `<bsdf>`).
    pub fn set_material(
        &mut self,
        base: &str,
        key: &Key,
        param: &str,
        value: &Value,
    ) -> Result<(), String> {
        let doc = parse(base)?;
        let (index, node) = materials::find(&doc, key)?;
        let element = materials::element_for(node, param, value)?;
        self.materials
            .retain(|(i, p, _)| !(*i == index && p == param));
        self.materials.push((index, param.to_string(), element));
        Ok(())
    }

    /// The base text with every edit applied.
    pub fn apply(&self, base: &str) -> Result<String, String> {
        let mut text = base.to_string();
        if self.integrator.is_some() || self.max_depth.is_some() {
            text = self.apply_integrator(&text)?;
        }
        if let Some(s) = &self.sampler {
            let doc = parse(&text)?;
            let sensor = sensor(&doc)?;
            let t = match children_tagged(sensor, "sampler").next() {
                Some(n) => set_attribute(&text, n, "type", s),
                None => insert_first_child(
                    &text,
                    sensor,
                    &format!("<sampler type=\"{}\"/>", crate::xml_text::escape(s)),
                ),
            };
            text = t;
        }
        for (index, param, element) in &self.materials {
            let doc = parse(&text)?;
            let (_, node) = materials::find(&doc, &Key::Index(*index))?;
            let t = match named_child(node, param) {
                Some(c) => splice(&text, c.range(), element),
                None => insert_first_child(&text, node, element),
            };
            text = t;
        }
        if let Some(pose) = &self.camera {
            let doc = parse(&text)?;
            let sensor = sensor(&doc)?;
            let xml = pose.to_world_xml("to_world");
            let t = match named_child(sensor, "to_world") {
                Some(t) => splice(&text, t.range(), &xml),
                None => insert_first_child(&text, sensor, &xml),
            };
            text = t;
        }
        Ok(text)
    }

    fn apply_integrator(&self, text: &str) -> Result<String, String> {
        let mut text = text.to_string();
        let doc = parse(&text)?;
        let root = doc.root_element();
        if children_tagged(root, "integrator").next().is_none() {
            text = insert_first_child(&text, root, "<integrator type=\"path\"/>");
        }
        if let Some(ty) = &self.integrator {
            let doc = parse(&text)?;
            let node = children_tagged(doc.root_element(), "integrator")
                .next()
                .ok_or("the integrator vanished")?;
            let t = set_attribute(&text, node, "type", ty);
            // Parameters the new type does not declare would be refused by the loader.
            let doc = parse(&t)?;
            let node = children_tagged(doc.root_element(), "integrator")
                .next()
                .ok_or("the integrator vanished")?;
            let decl = tessera_scene::plugin_declaration("integrator", ty)
                .ok_or_else(|| format!("unknown integrator \"{ty}\""))?;
            let drop: Vec<_> = node
                .children()
                .filter(|c| c.is_element())
                .filter(|c| {
                    c.attribute("name")
                        .is_some_and(|n| !decl.params.iter().any(|p| p.name == n))
                })
                .map(|c| c.range())
                .collect();
            text = drop.into_iter().rev().fold(t, |acc, r| splice(&acc, r, ""));
        }
        if let Some(d) = self.max_depth {
            let doc = parse(&text)?;
            let node = children_tagged(doc.root_element(), "integrator")
                .next()
                .ok_or("the integrator vanished")?;
            let ty = node.attribute("type").unwrap_or("path");
            let takes = tessera_scene::plugin_declaration("integrator", ty)
                .is_some_and(|decl| decl.params.iter().any(|p| p.name == "max_depth"));
            if !takes {
                return Err(format!("integrator \"{ty}\" takes no max_depth"));
            }
            let element = format!("<integer name=\"max_depth\" value=\"{d}\"/>");
            let t = match named_child(node, "max_depth") {
                Some(c) => splice(&text, c.range(), &element),
                None => insert_first_child(&text, node, &element),
            };
            text = t;
        }
        Ok(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = r#"<scene version="3.0.0">
    <default name="d" value="3"/>
    <integrator type="path"><integer name="max_depth" value="$d"/><integer name="rr_depth" value="2"/></integrator>
    <sensor type="perspective"><film type="hdrfilm"/></sensor>
    <bsdf type="twosided" id="a"><bsdf type="diffuse"/></bsdf>
</scene>"#;

    #[test]
    fn edits_rewrite_only_what_they_name() {
        let mut e = Edits::default();
        e.set_material(
            SCENE,
            &Key::Index(1),
            "reflectance",
            &Value::Rgb([0.1, 0.2, 0.3]),
        )
        .unwrap();
        e.integrator = Some("direct".into());
        let t = e.apply(SCENE).unwrap();
        assert!(
            t.contains("<integrator type=\"direct\"></integrator>"),
            "{t}"
        );
        assert!(
            t.contains("<rgb name=\"reflectance\" value=\"0.1, 0.2, 0.3\"/>"),
            "{t}"
        );
        assert!(t.contains("<default name=\"d\" value=\"3\"/>"));
        // Out of range, unknown parameter, unknown id: refused, nothing recorded.
        let bad = Value::Rgb([1.5, 0.0, 0.0]);
        assert!(e
            .set_material(SCENE, &Key::Index(1), "reflectance", &bad)
            .is_err());
        assert!(e
            .set_material(SCENE, &Key::Index(1), "shine", &Value::Float(1.0))
            .is_err());
        assert!(e
            .set_material(SCENE, &Key::Id("zz".into()), "reflectance", &bad)
            .is_err());
        assert_eq!(e.materials.len(), 1);
        e.integrator = None;
        e.max_depth = Some(-1);
        let t = e.apply(SCENE).unwrap();
        assert!(t.contains("<integer name=\"max_depth\" value=\"-1\"/><integer name=\"rr_depth\""));
    }

    #[test]
    fn defines_are_baked_into_defaults() {
        let t = bake_defines(
            SCENE,
            &[("d".into(), "5".into()), ("new".into(), "x".into())],
        );
        let t = t.unwrap();
        assert!(t.contains("<default name=\"d\" value=\"5\"/>"));
        assert!(t.contains("<default name=\"new\" value=\"x\"/>"));
    }
}

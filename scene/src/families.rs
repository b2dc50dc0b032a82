//! Every family of plugins, in the order the reference lists them: the one place that names
//! them all, for what reads every family alike (the reference, the check for parameters
//! without effect).
use crate::plugin::{Declared, Param, Plugin};
use crate::xml::Kind;

/// One family: its element, its title in the reference, its plugins' declarations.
pub(crate) struct Family {
    /// The element (`<bsdf>`, ...).
    pub kind: Kind,
    /// Its section title in the reference.
    pub title: &'static str,
    /// Its plugins, in table order.
    pub plugins: Vec<Declared>,
}

fn family<B>(kind: Kind, title: &'static str, table: &[Plugin<B>]) -> Family {
    Family {
        kind,
        title,
        plugins: table.iter().map(Plugin::declared).collect(),
    }
}

/// Every family.
pub fn families() -> Vec<Family> {
    vec![
        family(
            Kind::Integrator,
            "Integrators",
            crate::integrator::INTEGRATORS,
        ),
        family(Kind::Sampler, "Samplers", crate::sampler::SAMPLERS),
        family(Kind::Sensor, "Sensors", crate::sensor::SENSORS),
        family(Kind::Film, "Films", crate::sensor::FILMS),
        family(
            Kind::RFilter,
            "Reconstruction filters",
            crate::filter::FILTERS,
        ),
        family(Kind::Shape, "Shapes", crate::shapes::SHAPES),
        family(Kind::Bsdf, "BSDFs", crate::materials::BSDFS),
        family(
            Kind::Texture,
            "Textures",
            crate::materials::texture::TEXTURES,
        ),
        family(Kind::Emitter, "Emitters", crate::emitters::EMITTERS),
        family(Kind::Medium, "Media", crate::media::MEDIA),
        family(Kind::Volume, "Volumes", crate::media::VOLUMES),
        family(Kind::Phase, "Phase functions", crate::media::PHASES),
    ]
}

/// The declared parameters of plugin `name` of element kind `kind`, if it is one.
pub(crate) fn declared_params(
    families: &[Family],
    kind: Kind,
    name: &str,
) -> Option<&'static [Param]> {
    families
        .iter()
        .find(|f| f.kind == kind)?
        .plugins
        .iter()
        .find(|p| p.is(name))
        .map(|p| p.params)
}

impl Family {
    /// Mitsuba 3's plugins of this family that the loader does not read, in Mitsuba's order.
    pub(crate) fn not_read(&self) -> Vec<&'static str> {
        crate::mitsuba_names::MITSUBA_PLUGINS
            .iter()
            .filter(|(k, _)| *k == self.kind)
            .flat_map(|(_, names)| names.iter().copied())
            .filter(|n| !self.plugins.iter().any(|p| p.is(n)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    fn warnings(body: &str) -> Vec<String> {
        let text = format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">{body}</sensor>\n</scene>\n"
        );
        crate::load_scene_str(&text, Path::new("/nowhere/w.xml"), &[])
            .unwrap_or_else(|e| panic!("{e}"))
            .warnings
    }

    #[test]
    fn parameters_without_effect_are_warned_where_given() {
        let w = warnings(
            "<film type=\"hdrfilm\"><string name=\"pixel_format\" value=\"rgba\"/></film>\
             <sampler type=\"independent\"/>",
        );
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].starts_with(
                "/nowhere/w.xml:2:49: \"pixel_format\" of film \"hdrfilm\" is accepted but ignored"
            ),
            "{w:?}"
        );
        // Control: the same scene without the parameter warns of nothing.
        let w = warnings("<film type=\"hdrfilm\"/><sampler type=\"independent\"/>");
        assert!(w.is_empty(), "{w:?}");
        // A perspective camera's focus distance (Mitsuba's cbox sets it) loads, with a warning.
        let w = warnings("<float name=\"focus_distance\" value=\"10\"/>");
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].starts_with("/nowhere/w.xml:2:28: \"focus_distance\" of sensor \"perspective\""),
            "{w:?}"
        );
    }

    /// Every plugin the loader reads that Mitsuba also has is in Mitsuba's list, and the
    /// families' "not read" lists exclude what the loader reads.
    #[test]
    fn not_read_is_mitsuba_minus_the_loader() {
        for f in crate::families::families() {
            for n in f.not_read() {
                assert!(crate::mitsuba_names::is_mitsuba_plugin(f.kind, n));
                assert!(!f.plugins.iter().any(|p| p.is(n)), "{n}");
            }
        }
        let shapes = crate::families::families()
            .into_iter()
            .find(|f| f.kind == crate::xml::Kind::Shape)
            .unwrap();
        let missing = shapes.not_read();
        assert!(
            missing.contains(&"sdfgrid")
                && !missing.contains(&"linearcurve")
                && !missing.contains(&"sphere")
                && !missing.contains(&"cylinder")
                && !missing.contains(&"instance")
                && !missing.contains(&"shapegroup"),
            "{missing:?}"
        );
    }
}

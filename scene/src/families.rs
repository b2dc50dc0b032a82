//! Every family's declared parameters by element kind and plugin name, for checks that walk a
//! whole scene tree after it is built (the parameters a file gives that have no effect).
use crate::plugin::{Param, Plugin};
use crate::xml::Kind;

fn params<B>(family: &'static [Plugin<B>], name: &str) -> Option<&'static [Param]> {
    family.iter().find(|p| p.is(name)).map(|p| p.params)
}

/// The declared parameters of plugin `name` of element kind `kind`, if it is one.
pub fn declared_params(kind: Kind, name: &str) -> Option<&'static [Param]> {
    match kind {
        Kind::Integrator => params(crate::integrator::INTEGRATORS, name),
        Kind::Sampler => params(crate::sampler::SAMPLERS, name),
        Kind::Sensor => params(crate::sensor::SENSORS, name),
        Kind::Film => params(crate::sensor::FILMS, name),
        Kind::RFilter => params(crate::filter::FILTERS, name),
        Kind::Shape => params(crate::shapes::SHAPES, name),
        Kind::Bsdf => params(crate::materials::BSDFS, name),
        Kind::Texture => params(crate::materials::texture::TEXTURES, name),
        Kind::Emitter => params(crate::emitters::EMITTERS, name),
        Kind::Scene | Kind::Test => None,
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
    }
}

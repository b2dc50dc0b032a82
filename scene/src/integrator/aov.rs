//! The wrappers that add image channels: Mitsuba 3's `aov` (surface variables such as depth,
//! normals and albedo, beside its nested integrators' images) and `moment` (each nested
//! integrator's XYZ and its square). Both render their first nested integrator as the colour
//! image (`aov` without one renders black, as Mitsuba 3 does); the spec read is that
//! integrator's, so the command line changes it as usual, and the extra channels are listed in
//! `IntegratorSpec::layers`, each rendered by an integrator of its own with the same seed and
//! sampler (so the same camera samples), or taken from the colour's own samples where its
//! integrator is the colour's, and written into a multichannel EXR.
//!
//! Channel names are Mitsuba 3.9.1's: a nested integrator is named by its `name` attribute or
//! `_arg_N` (N counting the wrapper's unnamed nested objects from 0); `aov` gives it
//! `NAME.R/G/B/A` and then the variables `NAME.T` (depth), `NAME.X/Y/Z` (position, normals,
//! dp_du, dp_dv), `NAME.U/V` (uv, duv_dx, duv_dy), `NAME.I` (prim_index, shape_index),
//! `NAME.R/G/B` (albedo); `moment` gives `NAME.X/Y/Z` per nested integrator, then the same
//! names prefixed by `m2_` for the squares.
use super::spec::{IntegratorBuild, IntegratorPlugin, IntegratorSpec, Layer, LayerSource, Nest};
use crate::plugin::{Param, Plugin, Range};
use crate::util::Result;
use crate::xml::{Kind, Object};
use tessera_core::integrator::{Aov, AovIntegrator, Integrator};

/// A variable and the suffixes of its channel names.
type AovChannels = (Aov, &'static [&'static str]);

/// The AOV types of Mitsuba 3.9.1, with the variable each renders.
const AOV_TYPES: &[(&str, AovChannels)] = &[
    ("albedo", (Aov::Albedo, &["R", "G", "B"])),
    ("depth", (Aov::Depth, &["T"])),
    ("position", (Aov::Position, &["X", "Y", "Z"])),
    ("uv", (Aov::Uv, &["U", "V"])),
    ("geo_normal", (Aov::GeoNormal, &["X", "Y", "Z"])),
    ("sh_normal", (Aov::ShNormal, &["X", "Y", "Z"])),
    ("dp_du", (Aov::DpDu, &["X", "Y", "Z"])),
    ("dp_dv", (Aov::DpDv, &["X", "Y", "Z"])),
    ("duv_dx", (Aov::DuvDx, &["U", "V"])),
    ("duv_dy", (Aov::DuvDy, &["U", "V"])),
    ("prim_index", (Aov::PrimIndex, &["I"])),
    ("shape_index", (Aov::ShapeIndex, &["I"])),
];

const AOVS: Param = Param::new(
    "aovs",
    crate::plugin::ParamType::String,
    crate::plugin::Default::Required,
    Range::Note(
        "comma-separated NAME:TYPE pairs; TYPE one of albedo, depth, position, uv, geo_normal, \
         sh_normal, dp_du, dp_dv, duv_dx, duv_dy, prim_index, shape_index",
    ),
    "the surface variables written as extra channels",
);

/// `aov`.
pub const AOV: IntegratorPlugin = Plugin {
    name: "aov",
    aliases: &[],
    doc: "Mitsuba 3's arbitrary output variables: extra EXR channels describing the first \
          surface each camera ray meets (averaged over a pixel's samples like the colour), after \
          each nested integrator's R, G, B and A; the colour image is the first nested \
          integrator's (black without one). PNG and PFM outputs get the colour only, with a \
          warning.",
    params: &[AOVS],
    nested: "zero or more `<integrator>` (not `aov` or `moment`), each written as channels \
             NAME.R/G/B/A",
    build: IntegratorBuild {
        read: read_aov,
        make: Some(|_| Integrator::Aov(AovIntegrator::new(Aov::Black, 1))),
    },
};

/// `moment`.
pub(crate) const MOMENT: IntegratorPlugin = Plugin {
    name: "moment",
    aliases: &[],
    doc: "Mitsuba 3's moment wrapper: the colour image is the first nested integrator's; extra \
          EXR channels NAME.X/Y/Z hold each nested integrator's mean XYZ and m2_NAME.X/Y/Z the \
          mean of its square (from which the pixel variance follows). PNG and PFM outputs get \
          the colour only, with a warning.",
    params: &[],
    nested: "one or more `<integrator>` (not `aov` or `moment`)",
    build: IntegratorBuild {
        read: read_moment,
        make: None,
    },
};

/// The nested integrators of a wrapper, each with its channel name prefix; wrappers and path
/// reuse are refused in them (a reusing path's samples depend on its neighbours', which the
/// layer renders do not share).
fn nested_specs(obj: &Object, nest: Nest) -> Result<Vec<(String, IntegratorSpec)>> {
    let mut out = Vec::new();
    let mut unnamed = 0;
    for child in &obj.children {
        if child.obj.kind != Kind::Integrator {
            continue;
        }
        child.mark_used();
        let spec = nest(Some(&child.obj))?;
        if spec.name == "aov" || spec.name == "moment" || !spec.layers.is_empty() {
            return Err(crate::error::InputError::at(
                &child.loc,
                format!(
                    "{} cannot be nested in {}",
                    child.obj.describe(),
                    obj.describe()
                ),
            ));
        }
        if spec.reuse {
            return Err(crate::error::InputError::at(
                &child.loc,
                format!(
                    "{} nested in {} cannot use reuse (path reuse is not supported with extra \
                     channels)",
                    child.obj.describe(),
                    obj.describe()
                ),
            ));
        }
        let name = child.name.clone().unwrap_or_else(|| {
            unnamed += 1;
            format!("_arg_{}", unnamed - 1)
        });
        out.push((name, spec));
    }
    Ok(out)
}

fn names(prefix: &str, suffixes: &[&str]) -> Vec<String> {
    suffixes.iter().map(|s| format!("{prefix}.{s}")).collect()
}

fn read_aov(obj: &Object, spec: &mut IntegratorSpec, nest: Nest) -> Result<()> {
    let text = AOVS.read_string(obj)?;
    let loc = obj
        .prop(AOVS.name)
        .map_or(obj.loc.clone(), |p| p.loc.clone());
    let nested = nested_specs(obj, nest)?;
    let mut layers = Vec::new();
    for (k, (name, nested)) in nested.iter().enumerate() {
        let escaped_count = nested.name.starts_with("path") && !nested.hide_emitters;
        layers.push(Layer {
            names: names(name, &["R", "G", "B"]),
            source: LayerSource::Nested(Box::new(nested.clone())),
            // The first nested integrator renders the colour image.
            colour: k == 0,
        });
        layers.push(Layer {
            names: names(name, &["A"]),
            source: LayerSource::Aov(Aov::Alpha { escaped_count }),
            colour: false,
        });
    }
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (name, kind) = match item.split_once(':') {
            Some((n, k)) if !n.trim().is_empty() && !k.trim().is_empty() => (n.trim(), k.trim()),
            _ => {
                return Err(crate::error::InputError::at(
                    &loc,
                    format!("aov \"{item}\" is not a NAME:TYPE pair (e.g. dd.y:depth)"),
                ))
            }
        };
        let Some((_, (aov, suffixes))) = AOV_TYPES.iter().find(|t| t.0 == kind) else {
            let valid: Vec<&str> = AOV_TYPES.iter().map(|t| t.0).collect();
            return Err(crate::error::InputError::at(
                &loc,
                format!("unknown aov type \"{kind}\" (valid: {})", valid.join(", ")),
            ));
        };
        let (aov, suffixes) = (*aov, *suffixes);
        layers.push(Layer {
            names: names(name, suffixes),
            source: LayerSource::Aov(aov),
            colour: false,
        });
    }
    if layers.is_empty() {
        spec.warnings.push(format!(
            "{}: {} gives no aovs and no nested integrator: the image is black",
            obj.loc,
            obj.describe()
        ));
    }
    if let Some((_, first)) = nested.into_iter().next() {
        *spec = first;
    }
    spec.layers = layers;
    Ok(())
}

fn read_moment(obj: &Object, spec: &mut IntegratorSpec, nest: Nest) -> Result<()> {
    let nested = nested_specs(obj, nest)?;
    let Some((_, first)) = nested.first() else {
        return Err(obj.error("a moment integrator needs a nested <integrator>"));
    };
    let mut layers = Vec::new();
    for square in [false, true] {
        for (k, (name, n)) in nested.iter().enumerate() {
            let prefix = match square {
                true => format!("m2_{name}"),
                false => name.clone(),
            };
            layers.push(Layer {
                names: names(&prefix, &["X", "Y", "Z"]),
                source: LayerSource::Moment {
                    nested: Box::new(n.clone()),
                    square,
                },
                // The first nested integrator renders the colour image: its XYZ is the first
                // moment, and the colour's pass can square it for the second.
                colour: k == 0,
            });
        }
    }
    *spec = first.clone();
    spec.layers = layers;
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    fn load(integrator: &str) -> Result<crate::LoadedScene, crate::error::InputError> {
        let text = format!(
            "<scene version=\"3.0.0\">\n{integrator}\n<sensor type=\"perspective\"/>\n</scene>\n"
        );
        crate::load_scene_str(&text, Path::new("/nowhere/m.xml"), &[])
    }

    fn names(l: &crate::LoadedScene) -> Vec<String> {
        let layers = &l.integrator_spec.layers;
        layers.iter().flat_map(|l| l.names.clone()).collect()
    }

    /// Mitsuba 3.9.1's channel names (checked by running it): nested integrators first, by
    /// `name` or `_arg_N`, then the variables; the image is the first nested integrator's.
    #[test]
    fn aov_names_its_channels_as_mitsuba_does() {
        let l = load(
            "<integrator type=\"aov\">\n  <string name=\"aovs\" value=\"dd:depth, uv:uv\"/>\n  \
             <integrator type=\"path\" name=\"p1\">\n    <integer name=\"max_depth\" value=\"3\"/>\n  \
             </integrator>\n  <integrator type=\"direct\"/>\n</integrator>",
        )
        .unwrap();
        assert_eq!(l.integrator_spec.name, "path");
        assert_eq!(l.integrator_spec.max_depth, Some(3));
        assert_eq!(
            names(&l),
            [
                "p1.R", "p1.G", "p1.B", "p1.A", "_arg_0.R", "_arg_0.G", "_arg_0.B", "_arg_0.A",
                "dd.T", "uv.U", "uv.V"
            ]
        );
        // Without a nested integrator: the variables only, over a black image.
        let l = load(
            "<integrator type=\"aov\"><string name=\"aovs\" value=\"n:sh_normal\"/></integrator>",
        )
        .unwrap();
        assert_eq!(names(&l), ["n.X", "n.Y", "n.Z"]);
        let l = load(
            "<integrator type=\"aov\"><string name=\"aovs\" value=\"a:dp_du,b:dp_dv,c:duv_dx,\
             d:duv_dy,e:prim_index,f:shape_index\"/></integrator>",
        )
        .unwrap();
        assert_eq!(
            names(&l),
            ["a.X", "a.Y", "a.Z", "b.X", "b.Y", "b.Z", "c.U", "c.V", "d.U", "d.V", "e.I", "f.I"]
        );
        assert!(matches!(
            l.integrator,
            tessera_core::integrator::Integrator::Aov(_)
        ));
    }

    /// Bad `aovs` are located one-line errors that name the valid types.
    #[test]
    fn bad_aovs_are_located_errors() {
        for (aovs, words) in [
            (
                "dd:dpeth",
                "unknown aov type \"dpeth\" (valid: albedo, depth,",
            ),
            ("depth", "not a NAME:TYPE pair"),
        ] {
            let e = load(&format!(
                "<integrator type=\"aov\">\n  <string name=\"aovs\" value=\"{aovs}\"/>\n</integrator>"
            ))
            .unwrap_err()
            .to_string();
            assert!(
                e.starts_with("/nowhere/m.xml:3:3:") && e.contains(words),
                "{e}"
            );
            assert_eq!(e.lines().count(), 1, "{e}");
        }
        // Control: a valid list loads.
        load("<integrator type=\"aov\"><string name=\"aovs\" value=\"dd:depth\"/></integrator>")
            .unwrap();
        let e = load("<integrator type=\"aov\"/>").unwrap_err().to_string();
        assert!(
            e.starts_with("/nowhere/m.xml:2:1:") && e.contains("aovs"),
            "{e}"
        );
        let e = load(
            "<integrator type=\"aov\"><string name=\"aovs\" value=\"\"/>\n  \
             <integrator type=\"moment\"><integrator type=\"path\"/></integrator></integrator>",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("/nowhere/m.xml:3:3:") && e.contains("cannot be nested"),
            "{e}"
        );
        let e = load(
            "<integrator type=\"moment\">\n  <integrator type=\"path\">\n    \
             <boolean name=\"reuse\" value=\"true\"/></integrator></integrator>",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("/nowhere/m.xml:3:3:") && e.contains("reuse"),
            "{e}"
        );
    }

    /// `moment`: X, Y, Z per nested integrator, then the `m2_` squares; nothing nested is a
    /// located error; on the command line it names no integrator of its own.
    #[test]
    fn moment_names_its_channels_as_mitsuba_does() {
        let l = load(
            "<integrator type=\"moment\">\n  <integrator type=\"path\" name=\"a\">\n    \
             <integer name=\"max_depth\" value=\"3\"/>\n  </integrator>\n  \
             <integrator type=\"direct\" name=\"b\"/>\n</integrator>",
        )
        .expect("moment loads");
        assert_eq!(l.integrator_spec.name, "path");
        assert_eq!(l.integrator_spec.max_depth, Some(3));
        assert_eq!(
            names(&l),
            [
                "a.X", "a.Y", "a.Z", "b.X", "b.Y", "b.Z", "m2_a.X", "m2_a.Y", "m2_a.Z", "m2_b.X",
                "m2_b.Y", "m2_b.Z"
            ]
        );
        let mut l = l;
        let e = l.set_integrator(Some("moment"), None).unwrap_err();
        assert!(e.contains("wraps other integrators"), "{e}");
        let e = l.set_integrator(Some("aov"), None).unwrap_err();
        assert!(e.contains("wraps other integrators"), "{e}");
        l.set_integrator(Some("direct"), None)
            .expect("control: a real integrator");
        let e = load(
            "<integrator type=\"moment\">\n  <integrator type=\"path\">\n    \
             <integer name=\"max_depth\" value=\"-7\"/>\n  </integrator>\n</integrator>",
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("/nowhere/m.xml:4:5:"), "{e}");
        let e = load("<integrator type=\"moment\"/>")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("/nowhere/m.xml:2:1:") && e.contains("nested"),
            "{e}"
        );
    }
}

//! The plugin names Mitsuba 3.9.1 defines in each family Tessera reads, so that the reference can
//! list the ones Tessera does not read (the families compute that against the loader's tables,
//! so it cannot drift from them) and an unknown name can be told apart from a typo: "a Mitsuba 3 plugin Tessera
//! does not read" rather than "unknown".
use crate::xml::Kind;

/// Mitsuba 3.9.1's plugins per element (its `src/<family>/*.cpp`).
pub(crate) const MITSUBA_PLUGINS: &[(Kind, &[&str])] = &[
    (
        Kind::Integrator,
        &[
            "aov",
            "depth",
            "direct",
            "moment",
            "path",
            "ptracer",
            "stokes",
            "volpath",
            "volpathmis",
        ],
    ),
    (
        Kind::Sampler,
        &[
            "independent",
            "ldsampler",
            "multijitter",
            "orthogonal",
            "stratified",
        ],
    ),
    (
        Kind::Sensor,
        &[
            "batch",
            "distant",
            "irradiancemeter",
            "orthographic",
            "perspective",
            "radiancemeter",
            "thinlens",
        ],
    ),
    (Kind::Film, &["hdrfilm", "specfilm"]),
    (
        Kind::RFilter,
        &[
            "box",
            "catmullrom",
            "gaussian",
            "lanczos",
            "mitchell",
            "tent",
        ],
    ),
    (
        Kind::Shape,
        &[
            "bsplinecurve",
            "cube",
            "cylinder",
            "disk",
            "ellipsoids",
            "ellipsoidsmesh",
            "instance",
            "linearcurve",
            "merge",
            "obj",
            "ply",
            "rectangle",
            "sdfgrid",
            "serialized",
            "shapegroup",
            "sphere",
        ],
    ),
    (
        Kind::Bsdf,
        &[
            "blendbsdf",
            "bumpmap",
            "circular",
            "conductor",
            "dielectric",
            "diffuse",
            "hair",
            "mask",
            "measured",
            "measured_polarized",
            "normalmap",
            "null",
            "plastic",
            "polarizer",
            "pplastic",
            "principled",
            "principledthin",
            "retarder",
            "roughconductor",
            "roughdielectric",
            "roughplastic",
            "thindielectric",
            "twosided",
        ],
    ),
    (
        Kind::Texture,
        &["bitmap", "checkerboard", "mesh_attribute", "volume"],
    ),
    (Kind::Medium, &["heterogeneous", "homogeneous"]),
    (Kind::Volume, &["constvolume", "gridvolume"]),
    (
        Kind::Phase,
        &[
            "blendphase",
            "hg",
            "isotropic",
            "rayleigh",
            "sggx",
            "tabphase",
        ],
    ),
    (
        Kind::Emitter,
        &[
            "area",
            "constant",
            "directional",
            "directionalarea",
            "envmap",
            "point",
            "projector",
            "spot",
            "sunsky",
            "timed_sunsky",
        ],
    ),
];

/// Whether `name` is one of Mitsuba 3's plugins of element `kind`.
pub(crate) fn is_mitsuba_plugin(kind: Kind, name: &str) -> bool {
    MITSUBA_PLUGINS
        .iter()
        .any(|(k, names)| *k == kind && names.contains(&name))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    fn error(shape: &str) -> String {
        let text = format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<shape type=\"{shape}\"/>\n</scene>\n"
        );
        crate::load_scene_str(&text, Path::new("/nowhere/n.xml"), &[])
            .unwrap_err()
            .to_string()
    }

    /// A Mitsuba plugin Tessera lacks is named as such; a typo is unknown (the control).
    #[test]
    fn a_mitsuba_plugin_is_told_apart_from_a_typo() {
        let e = error("sdfgrid");
        assert!(e.starts_with("/nowhere/n.xml:3:1:"), "{e}");
        assert!(
            e.contains("Mitsuba 3's shape \"sdfgrid\", which Tessera does not read yet"),
            "{e}"
        );
        let e = error("sdfgri");
        assert!(
            e.contains("unknown shape \"sdfgri\" (Tessera reads:"),
            "{e}"
        );
    }
}

//! The Nori / Wakame (and old Mitsuba 0.x) dialects, mapped onto Mitsuba 3 vocabulary.
//!
//! Element aliases: `<mesh>` is `<shape>`, `<camera>` is `<sensor>`, `<color>` is `<rgb>`.
//! Parameter names are converted from camelCase to snake_case (`toWorld` -> `to_world`,
//! `intIOR` -> `int_ior`), which is also what Mitsuba 3 does when it upgrades 0.x files. One
//! Mitsuba 3 plugins have upper-case parameter names, the `mitchell` filter's `B` and `C` and the
//! `sggx` phase function's `S`: those are kept. Nori's `albedo` on a diffuse BSDF is Mitsuba's `reflectance`.

use super::object::Kind;

/// The Mitsuba element name for an element name as written.
pub(crate) fn element_alias(tag: &str) -> &str {
    match tag {
        "mesh" => "shape",
        "camera" => "sensor",
        "color" => "rgb",
        other => other,
    }
}

/// camelCase to snake_case: an underscore goes before an upper-case letter that follows a
/// lower-case letter or digit, then everything is lower-cased (`intIOR` -> `int_ior`).
pub fn snake_case(name: &str) -> String {
    if !name.bytes().any(|b| b.is_ascii_uppercase()) {
        return name.to_string();
    }
    let mut out = String::with_capacity(name.len() + 4);
    let mut prev: Option<char> = None;
    for c in name.chars() {
        if c.is_ascii_uppercase() {
            if prev.is_some_and(|p| p.is_ascii_lowercase() || p.is_ascii_digit()) {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else {
            out.push(c);
        }
        prev = Some(c);
    }
    out
}

/// Mitsuba 3's own upper-case parameter names: (kind, plugin, name), kept as written.
const UPPER_CASE_PARAMS: &[(Kind, &str, &str)] = &[
    (Kind::RFilter, "mitchell", "B"),
    (Kind::RFilter, "mitchell", "C"),
    (Kind::Phase, "sggx", "S"),
];

/// The normalized name of a parameter (property or named child) of an object of `kind` with
/// plugin type `plugin`.
pub(crate) fn param_name(name: &str, kind: Kind, plugin: &str) -> String {
    if UPPER_CASE_PARAMS.contains(&(kind, plugin, name)) {
        return name.to_string();
    }
    let name = snake_case(name);
    if kind == Kind::Bsdf && plugin == "diffuse" && name == "albedo" {
        return "reflectance".to_string();
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nori_names() {
        for (nori, mitsuba) in [
            ("toWorld", "to_world"),
            ("sampleCount", "sample_count"),
            ("maxDepth", "max_depth"),
            ("rrDepth", "rr_depth"),
            ("intIOR", "int_ior"),
            ("extIOR", "ext_ior"),
            ("nearClip", "near_clip"),
            ("to_world", "to_world"),
            ("alpha_u", "alpha_u"),
        ] {
            assert_eq!(snake_case(nori), mitsuba);
        }
        assert_eq!(param_name("albedo", Kind::Bsdf, "diffuse"), "reflectance");
        assert_eq!(param_name("albedo", Kind::Bsdf, "principled"), "albedo");
        assert_eq!(param_name("albedo", Kind::Shape, "diffuse"), "albedo");
        // Mitsuba 3's own upper-case names stay, only on their plugins.
        assert_eq!(param_name("B", Kind::RFilter, "mitchell"), "B");
        assert_eq!(param_name("S", Kind::Phase, "sggx"), "S");
        assert_eq!(param_name("S", Kind::Phase, "hg"), "s");
        assert_eq!(element_alias("mesh"), "shape");
        assert_eq!(element_alias("camera"), "sensor");
        assert_eq!(element_alias("color"), "rgb");
        assert_eq!(element_alias("bsdf"), "bsdf");
    }
}

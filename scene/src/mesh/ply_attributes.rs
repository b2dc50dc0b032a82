//! Which mesh attributes Mitsuba 3.9.1's `ply` shape makes of a PLY element's extra properties
//! (those that are not positions, normals, texture coordinates or face indices), by its naming
//! rules as read in its sources and checked by loading files with it:
//!
//! - `r`, `g`, `b` (and `a`), or `red`, `green`, `blue` (and `alpha`), become `{vertex|face}_color`;
//! - consecutive properties `PREFIX_c` whose one-letter suffixes run through one of the
//!   sequences `x y z w`, `r g b a`, `0 1 2 3` or `1 2 3 4` become one attribute
//!   `{vertex|face}_PREFIX` (`..._PREFIX_color` for `r g b a`) when there are 1 or 3 of them;
//!   any other count, a suffix that starts no sequence, a property without `_` or with a longer
//!   suffix, and a prefix met before make nothing (Mitsuba warns).
//!
//! Their presence also decides how Mitsuba lists the mesh (`crate::shape_numbering`); their
//! values are what `mesh_attribute` textures read.

/// The suffix sequences, by position: column `k` of each row is sequence `k`'s letter there.
const SUFFIXES: [&[u8; 4]; 4] = [b"xr01", b"yg12", b"zb23", b"wa34"];

/// The attributes Mitsuba makes of `fields`, the property names of a PLY element in file order
/// (a list property `NAME` written as `NAME.count`, `i0`, `i1`, `i2`, as Mitsuba's reader
/// expands it); `kind` is `"vertex"` or `"face"`. Each is its name and the positions in
/// `fields` of its components, in order.
pub(crate) fn mitsuba_attributes(kind: &str, fields: &[String]) -> Vec<(String, Vec<usize>)> {
    let mut fields: Vec<String> = fields.to_vec();
    let has = |f: &[String], n: &str| f.iter().any(|x| x == n);
    let mut reserved: Vec<&str> = match kind {
        "vertex" => vec!["x", "y", "z", "nx", "ny", "nz", "u", "v"],
        _ => vec![
            "vertex_index.count",
            "vertex_indices.count",
            "i0",
            "i1",
            "i2",
        ],
    };
    if kind == "vertex" && !(has(&fields, "u") && has(&fields, "v")) {
        for (a, b) in [("texture_u", "texture_v"), ("s", "t")] {
            if has(&fields, a) && has(&fields, b) {
                rename(&mut fields, a, "u");
                rename(&mut fields, b, "v");
                break;
            }
        }
    }
    let mut out = Vec::new();
    let prefix = format!("{kind}_");
    if !(has(&fields, "r") && has(&fields, "g") && has(&fields, "b"))
        && has(&fields, "red")
        && has(&fields, "green")
        && has(&fields, "blue")
    {
        for (a, b) in [("red", "r"), ("green", "g"), ("blue", "b"), ("alpha", "a")] {
            rename(&mut fields, a, b);
        }
    }
    if has(&fields, "r") && has(&fields, "g") && has(&fields, "b") {
        let at = |n: &str| fields.iter().position(|x| x == n);
        let parts = ["r", "g", "b", "a"].iter().filter_map(|n| at(n)).collect();
        out.push((format!("{prefix}color"), parts));
    }
    reserved.extend(["r", "g", "b", "a"]);

    let mut seen: Vec<String> = Vec::new();
    // The attribute being read: its prefix, its suffix sequence and its components so far.
    let mut current: Option<(String, usize)> = None;
    let mut parts: Vec<usize> = Vec::new();
    let mut level = 0;
    // Ends the attribute being read: one of 1 or 3 components becomes an attribute.
    let flush = |current: &mut Option<(String, usize)>,
                 parts: &mut Vec<usize>,
                 level: &mut usize,
                 seen: &mut Vec<String>,
                 out: &mut Vec<(String, Vec<usize>)>| {
        if let Some((p, seq)) = current.take() {
            if *level == 1 || *level == 3 {
                let color = if seq == 1 { "_color" } else { "" };
                out.push((format!("{prefix}{p}{color}"), core::mem::take(parts)));
                seen.push(p);
            }
        }
        parts.clear();
        *level = 0;
    };
    let mut i = 0;
    while i < fields.len() {
        let name = &fields[i];
        if reserved.contains(&name.as_str()) {
            i += 1;
            continue;
        }
        let Some((p, suffix)) = name.rsplit_once('_') else {
            flush(&mut current, &mut parts, &mut level, &mut seen, &mut out);
            i += 1;
            continue;
        };
        if suffix.len() != 1 {
            flush(&mut current, &mut parts, &mut level, &mut seen, &mut out);
            i += 1;
            continue;
        }
        if current.as_ref().is_some_and(|c| c.0 != p) {
            flush(&mut current, &mut parts, &mut level, &mut seen, &mut out);
        }
        let c = suffix.as_bytes()[0];
        match &current {
            None if seen.iter().any(|s| s == p) => {
                // A prefix met before: Mitsuba skips the properties that start with it, and
                // the one after them.
                let p = p.to_string();
                while i < fields.len() && fields[i].starts_with(&p) {
                    i += 1;
                }
                i += 1;
                continue;
            }
            None => match SUFFIXES[0].iter().position(|&s| s == c) {
                Some(seq) => current = Some((p.to_string(), seq)),
                None => {
                    i += 1;
                    continue;
                }
            },
            Some((_, seq)) => {
                if level >= SUFFIXES.len() || SUFFIXES[level][*seq] != c {
                    // A broken sequence: nothing is made of it.
                    current = None;
                    parts.clear();
                    level = 0;
                    let p = p.to_string();
                    while i < fields.len() && fields[i].starts_with(&p) {
                        i += 1;
                    }
                    continue;
                }
            }
        }
        parts.push(i);
        level += 1;
        i += 1;
    }
    flush(&mut current, &mut parts, &mut level, &mut seen, &mut out);
    out
}

fn rename(fields: &mut [String], from: &str, to: &str) {
    if let Some(f) = fields.iter_mut().find(|f| *f == from) {
        *f = to.to_string();
    }
}

#[cfg(test)]
mod tests {
    use super::mitsuba_attributes;

    fn attrs(kind: &str, fields: &[&str]) -> Vec<(String, usize)> {
        let fields: Vec<String> = fields.iter().map(|s| s.to_string()).collect();
        let mut a: Vec<(String, usize)> = mitsuba_attributes(kind, &fields)
            .into_iter()
            .map(|(n, parts)| (n, parts.len()))
            .collect();
        a.sort();
        a
    }

    fn named(list: &[(&str, usize)]) -> Vec<(String, usize)> {
        list.iter().map(|(n, k)| (n.to_string(), *k)).collect()
    }

    /// What Mitsuba 3.9.1 made of these properties (loaded with it; `has_attribute`).
    #[test]
    fn attributes_are_named_as_mitsuba_names_them() {
        let v = |extra: &[&'static str]| -> Vec<&'static str> {
            let mut f = vec!["x", "y", "z"];
            f.extend_from_slice(extra);
            f
        };
        assert_eq!(
            attrs("vertex", &v(&["r", "g", "b"])),
            named(&[("vertex_color", 3)])
        );
        assert_eq!(
            attrs("vertex", &v(&["red", "green", "blue", "alpha"])),
            named(&[("vertex_color", 4)])
        );
        assert_eq!(
            attrs("vertex", &v(&["color_0", "color_1", "color_2"])),
            named(&[("vertex_color", 3)])
        );
        let face = ["vertex_indices.count", "i0", "i1", "i2"];
        let mut f = face.to_vec();
        f.extend(["color_0", "color_1", "color_2", "weight_0"]);
        assert_eq!(
            attrs("face", &f),
            named(&[("face_color", 3), ("face_weight", 1)])
        );
        assert_eq!(
            attrs(
                "vertex",
                &v(&["foo_r", "foo_g", "foo_b", "bar_x", "baz_1", "baz_2", "baz_3"])
            ),
            named(&[
                ("vertex_bar", 1),
                ("vertex_baz", 3),
                ("vertex_foo_color", 3)
            ])
        );
        let mut f = face.to_vec();
        f.extend(["q_x", "q_y"]);
        assert_eq!(attrs("face", &f), named(&[]));
        assert_eq!(
            attrs("vertex", &v(&["nx", "ny", "nz", "s", "t", "temp", "w_a"])),
            named(&[])
        );
        let mut f = face.to_vec();
        f.extend(["a_x", "a_y", "a_z", "a_w"]);
        assert_eq!(attrs("face", &f), named(&[]));
        // Control: the plain properties make nothing.
        assert_eq!(
            attrs("vertex", &v(&["nx", "ny", "nz", "u", "v"])),
            named(&[])
        );
    }
}

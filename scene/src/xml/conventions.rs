//! Which renderer's conventions a scene file follows, where renderers that read the same words
//! draw different images.
//!
//! Nori and Wakame (the Java port of Nori used in McGill's course) read the same XML, but
//! Wakame's perspective camera maps the film's x axis with the opposite sign: the image it
//! renders of a file is the mirror image, left to right, of the image Nori (and Mitsuba 3, and
//! Tessera by default) renders of it. A file's conventions are chosen, in order of precedence,
//! by the command line's `--dialect`, then by a processing instruction in the file's prolog,
//!
//! ```xml
//! <?xml version="1.0"?>
//! <?tessera dialect="wakame"?>
//! <scene> ... </scene>
//! ```
//!
//! (which Nori's, Wakame's and Mitsuba's parsers all skip), else Nori's, which are also
//! Mitsuba 3's.

use std::fmt;

use crate::error::{InputError, Loc};
use glam::{Mat4, Vec3};
use tessera_core::math::Transform;

/// The conventions a scene file is rendered with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dialect {
    /// Nori's and Mitsuba 3's: the default.
    #[default]
    Nori,
    /// Wakame's: the film's x axis mirrored.
    Wakame,
}

impl Dialect {
    /// Every dialect, in the order messages list them.
    pub(crate) const ALL: [Dialect; 2] = [Dialect::Nori, Dialect::Wakame];

    /// The dialect's name on the command line and in the processing instruction.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Nori => "nori",
            Dialect::Wakame => "wakame",
        }
    }

    /// The dialect named `name`, or a message listing the names.
    pub fn parse(name: &str) -> Result<Dialect, String> {
        Dialect::ALL
            .into_iter()
            .find(|d| d.name() == name)
            .ok_or_else(|| {
                let names: Vec<_> = Dialect::ALL.iter().map(|d| d.name()).collect();
                format!(
                    "unknown dialect \"{name}\" (expected {})",
                    names.join(" or ")
                )
            })
    }

    /// The camera placement that renders this dialect's image with Tessera's camera, from the
    /// placement the file gives: Wakame's mirrors the camera's local x axis (exactly: a sign
    /// flip of one column of the matrix and one row of its inverse).
    pub(crate) fn camera_to_world(self, to_world: Transform) -> Transform {
        match self {
            Dialect::Nori => to_world,
            Dialect::Wakame => {
                let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
                Transform {
                    m: to_world.m * mirror,
                    inv: mirror * to_world.inv,
                }
            }
        }
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The dialect a document's `<?tessera dialect="..."?>` processing instruction names, if it has
/// one before its root element. Processing instructions with other targets are skipped; a
/// `tessera` instruction with anything else in it is an error at its location.
pub(crate) fn read_instruction(
    doc: &roxmltree::Document<'_>,
    loc: impl Fn(usize) -> Loc,
) -> Result<Option<Dialect>, InputError> {
    let mut found = None;
    for node in doc.root().children() {
        let Some(pi) = node.pi() else { continue };
        if pi.target != "tessera" {
            continue;
        }
        let at = loc(node.range().start);
        let value = pi.value.unwrap_or("").trim();
        let name = value
            .strip_prefix("dialect=")
            .and_then(|v| {
                let quote = v.chars().next().filter(|c| *c == '"' || *c == '\'')?;
                v[1..].strip_suffix(quote)
            })
            .ok_or_else(|| {
                InputError::at(
                    &at,
                    format!(
                        "expected <?tessera dialect=\"nori|wakame\"?>, found <?tessera {value}?>"
                    ),
                )
            })?;
        let dialect = Dialect::parse(name).map_err(|m| InputError::at(&at, m))?;
        if found.replace(dialect).is_some() {
            return Err(InputError::at(
                &at,
                "a second <?tessera dialect=...?> instruction",
            ));
        }
    }
    Ok(found)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn names_round_trip() {
        for d in Dialect::ALL {
            assert_eq!(Dialect::parse(d.name()), Ok(d));
        }
        let e = Dialect::parse("mitsuba2").unwrap_err();
        assert!(e.contains("nori or wakame"), "{e}");
    }

    #[test]
    fn wakame_mirrors_local_x_exactly() {
        let m = Mat4::from_scale_rotation_translation(
            Vec3::new(1.0, 2.0, 0.5),
            Quat::from_rotation_y(0.7) * Quat::from_rotation_x(-0.3),
            Vec3::new(3.0, -1.0, 2.0),
        );
        let t = Transform::new(m).unwrap();
        let w = Dialect::Wakame.camera_to_world(t);
        let p = Vec3::new(0.3, -0.2, 1.0);
        let mirrored = Vec3::new(-p.x, p.y, p.z);
        assert_eq!(w.point(p), t.point(mirrored));
        assert_eq!(w.vector(p), t.vector(mirrored));
        // The inverse stays the inverse.
        let q = Vec3::new(1.0, 2.0, 3.0);
        assert!(
            (w.inv.transform_point3(w.m.transform_point3(q)) - q)
                .abs()
                .max_element()
                < 1e-5
        );
        let n = Dialect::Nori.camera_to_world(t);
        assert_eq!(n.m, t.m);
        assert_eq!(n.inv, t.inv);
    }
}

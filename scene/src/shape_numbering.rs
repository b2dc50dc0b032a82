//! Mitsuba 3.9.1's numbering of a scene's shapes, which its `aov` integrator's `shape_index`
//! and `prim_index` outputs give (`tessera_core::scene::ShapeNumbering`).
//!
//! What Mitsuba 3.9.1 does (checked by loading files with it): its parser merges equivalent
//! objects (two `<bsdf>`s written alike become one) and then gathers the scene's top-level
//! shapes into a `merge` shape, which joins the meshes that share a BSDF, emitter and the
//! presence of vertex normals and texture coordinates into one mesh (their triangles follow
//! one another in file order). `scene.shapes()` then lists the shapes that are not meshes
//! (spheres, disks, cylinders, instances, and meshes with mesh attributes, which a PLY file's
//! extra properties give and which are joined to nothing) in file order, then the meshes,
//! joined ones as one; shapes inside a `shapegroup` are not listed. `shape_index` is the
//! 1-based position in that list.
//!
//! The meshes' order in the list is the iteration order of a hash table keyed by pointers, so
//! it changes from run to run in Mitsuba itself; Tessera lists them by first appearance in the
//! file. A file with one mesh (or one set of joined meshes) is therefore numbered exactly as
//! Mitsuba numbers it. A shape without a `<bsdf>` gets a default BSDF of its own in Mitsuba,
//! so it joins nothing; nor does a shape that emits. The parts an OBJ with `use_mtl` is split
//! into (a Tessera extension) keep their source shape's number, their triangles numbered on
//! from one part to the next.
use crate::xml::{Child, Object, Value};
use std::collections::HashMap;
use std::fmt::Write;
use tessera_core::geometry::{Shape, ShapeKind};
use tessera_core::scene::{ShapeNumber, ShapeNumbering};

/// One top-level shape of the file as Mitsuba lists it.
enum Entry {
    /// Not a mesh (or an instance): numbered in file order, first.
    Plain {
        shapes: Vec<u32>,
        instance: Option<u32>,
    },
    /// A mesh: Tessera's shapes it became, whether it is a `rectangle`, and what it joins
    /// other meshes by (`None`: nothing).
    Mesh {
        shapes: Vec<u32>,
        rectangle: bool,
        join: Option<String>,
    },
    /// A member of a shape group: unlisted, but a rectangle's triangles are still numbered
    /// as Mitsuba's.
    Member { shapes: Vec<u32>, rectangle: bool },
}

/// The top-level shapes met so far, in file order.
#[derive(Default)]
pub(crate) struct Numbering {
    entries: Vec<Entry>,
}

impl Numbering {
    /// Records the top-level shape `obj`, which became Tessera's shapes `added` (indices
    /// into `shapes`); `bsdf` is its `<bsdf>`, if it names one; `attributed`: its mesh file
    /// gave Mitsuba mesh attributes, so Mitsuba joins it to nothing and lists it with the
    /// shapes that are not meshes.
    pub(crate) fn shape(
        &mut self,
        obj: &Object,
        bsdf: Option<&Child>,
        attributed: bool,
        added: &[u32],
        shapes: &[Shape],
    ) {
        let Some(&first) = added.first() else {
            return;
        };
        let shape = &shapes[first as usize];
        let (ShapeKind::Mesh(m), false) = (&shape.kind, attributed) else {
            self.entries.push(Entry::Plain {
                shapes: added.to_vec(),
                instance: None,
            });
            return;
        };
        let join = match (bsdf, shape.emitter) {
            (Some(b), None) => Some(format!(
                "{}|{}|{}",
                structure(&b.obj),
                !m.normals.is_empty(),
                !m.uvs.is_empty()
            )),
            _ => None,
        };
        self.entries.push(Entry::Mesh {
            shapes: added.to_vec(),
            rectangle: obj.plugin == "rectangle",
            join,
        });
    }

    /// Records the shape-group member `obj`, which became Tessera's shapes `added`.
    pub(crate) fn member(&mut self, obj: &Object, added: &[u32]) {
        self.entries.push(Entry::Member {
            shapes: added.to_vec(),
            rectangle: obj.plugin == "rectangle",
        });
    }

    /// Records instance number `instance`.
    pub(crate) fn instance(&mut self, instance: u32) {
        self.entries.push(Entry::Plain {
            shapes: Vec::new(),
            instance: Some(instance),
        });
    }

    /// The numbering of `shapes` (shapes no entry names, the members of shape groups, get 0)
    /// and of `instances` instances.
    pub(crate) fn finish(self, shapes: &[Shape], instances: usize) -> ShapeNumbering {
        let mut out = ShapeNumbering {
            shapes: vec![
                ShapeNumber {
                    index: 0,
                    prim_offset: 0,
                    rectangle: false,
                };
                shapes.len()
            ],
            instances: vec![0; instances],
        };
        let mut next = 1;
        for e in &self.entries {
            if let Entry::Member { shapes, rectangle } = e {
                for &s in shapes {
                    out.shapes[s as usize].rectangle = *rectangle;
                }
            }
            if let Entry::Plain { shapes, instance } = e {
                for &s in shapes {
                    out.shapes[s as usize].index = next;
                }
                if let Some(i) = instance {
                    out.instances[*i as usize] = next;
                }
                next += 1;
            }
        }
        // Joined meshes: number and triangles so far, by what they join by.
        let mut joined: HashMap<&str, (u32, u32)> = HashMap::new();
        for e in &self.entries {
            let Entry::Mesh {
                shapes: added,
                rectangle,
                join,
            } = e
            else {
                continue;
            };
            let mut own;
            let slot = match join {
                Some(k) => joined.entry(k.as_str()).or_insert_with(|| {
                    next += 1;
                    (next - 1, 0)
                }),
                None => {
                    own = (next, 0);
                    next += 1;
                    &mut own
                }
            };
            for &s in added {
                out.shapes[s as usize] = ShapeNumber {
                    index: slot.0,
                    prim_offset: slot.1,
                    rectangle: *rectangle,
                };
                if let ShapeKind::Mesh(m) = &shapes[s as usize].kind {
                    slot.1 += m.indices.len() as u32;
                }
            }
        }
        out
    }
}

/// What makes two objects equivalent to Mitsuba's parser: plugin, properties and nested
/// objects, whatever their place in the file.
fn structure(obj: &Object) -> String {
    let mut s = format!("{:?}:{}(", obj.kind, obj.plugin);
    for p in &obj.props {
        let v = match &p.value {
            Value::Transform(m) => format!("{:?}", m.to_cols_array()),
            v => format!("{v:?}"),
        };
        let _ = write!(s, "{}={v};", p.name);
    }
    for c in &obj.children {
        let _ = write!(
            s,
            "{}={};",
            c.name.as_deref().unwrap_or(""),
            structure(&c.obj)
        );
    }
    s.push(')');
    s
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use tessera_core::scene::ShapeNumber;

    fn number(index: u32, prim_offset: u32, rectangle: bool) -> ShapeNumber {
        ShapeNumber {
            index,
            prim_offset,
            rectangle,
        }
    }

    /// Mitsuba 3.9.1's `scene.shapes()` for this file (checked by loading it with Mitsuba):
    /// the sphere, the instance and the disk first, in file order; then two meshes: `a` and `c`
    /// share a BSDF (written twice alike, which the parser merges), so they are one mesh of 4
    /// triangles, `c`'s after `a`'s; `b` has a default BSDF of its own and joins nothing. The
    /// group's rectangle is not listed. The two meshes' order is Tessera's (file order; Mitsuba
    /// listed `b` first, by its hash table).
    #[test]
    fn shapes_are_numbered_as_mitsuba_lists_them() {
        let b = "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2\"/></bsdf>";
        let text = format!(
            "<scene version=\"3.0.0\"><sensor type=\"perspective\"/>\
             <shape type=\"rectangle\" id=\"a\">{b}</shape>\
             <shape type=\"sphere\"/>\
             <shape type=\"shapegroup\" id=\"g\"><shape type=\"rectangle\"/></shape>\
             <shape type=\"rectangle\" id=\"b\"/>\
             <shape type=\"instance\"><ref id=\"g\"/></shape>\
             <shape type=\"rectangle\" id=\"c\">{b}</shape>\
             <shape type=\"disk\"/></scene>"
        );
        let l = crate::load_scene_str(&text, Path::new("/nowhere/n.xml"), &[]).unwrap();
        let n = &l.scene.shape_numbering;
        // Tessera's shapes: a, sphere, the group's rectangle, b, c, disk.
        assert_eq!(
            n.shapes,
            [
                number(4, 0, true),
                number(1, 0, false),
                number(0, 0, true),
                number(5, 0, true),
                number(4, 2, true),
                number(3, 0, false),
            ]
        );
        assert_eq!(n.instances, [2]);
        // Control: with different BSDFs, `a` and `c` are not joined.
        let text = text.replacen("0.2", "0.3", 1);
        let l = crate::load_scene_str(&text, Path::new("/nowhere/n.xml"), &[]).unwrap();
        assert_eq!(l.scene.shape_numbering.shapes[4], number(6, 0, true));
    }

    /// Mitsuba 3.9.1 (checked by loading the same file) lists a PLY with colours among the
    /// shapes that are not meshes, in file order: `p`, then the sphere, then the rectangles.
    #[test]
    fn a_mesh_with_attributes_is_listed_with_the_shapes_that_are_not_meshes() {
        let dir = std::env::temp_dir().join(format!("tessera-numbering-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let write = |name: &str, extra: &[&str]| {
            let mut text = String::from("ply\nformat ascii 1.0\nelement vertex 3\n");
            for p in ["x", "y", "z"].iter().chain(extra) {
                text += &format!("property float {p}\n");
            }
            text += "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
            for v in ["0 0 0", "1 0 0", "0 1 0"] {
                text += &format!("{v}{}\n", " 0.5".repeat(extra.len()));
            }
            text += "3 0 1 2\n";
            std::fs::write(dir.join(name), text).unwrap();
        };
        write("coloured.ply", &["red", "green", "blue"]);
        write("plain.ply", &[]);
        let scene = |ply: &str| {
            let text = format!(
                "<scene version=\"3.0.0\"><sensor type=\"perspective\"/>\
                 <shape type=\"rectangle\"/>\
                 <shape type=\"ply\"><string name=\"filename\" value=\"{ply}\"/></shape>\
                 <shape type=\"sphere\"/><shape type=\"rectangle\"/></scene>"
            );
            let l = crate::load_scene_str(&text, &dir.join("s.xml"), &[]).unwrap();
            let n = l.scene.shape_numbering.shapes;
            n.iter().map(|s| s.index).collect::<Vec<_>>()
        };
        // Tessera's shapes: rectangle, ply, sphere, rectangle.
        assert_eq!(scene("coloured.ply"), [3, 1, 2, 4]);
        // Control: without colours the PLY is a mesh like the rectangles.
        assert_eq!(scene("plain.ply"), [2, 3, 1, 4]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

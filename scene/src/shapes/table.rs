//! The shape family's table and the builder that finds a shape's plugin and its attached
//! `<bsdf>` and `<emitter>`: the one file that knows every shape plugin.
use super::mesh_file::{OBJ, PLY, SERIALIZED};
use super::simple::{CUBE, DISK, RECTANGLE, SPHERE};
use super::{curve, cylinder, instancing, Geometry, MtlPart, ShapePlugin, FLIP_NORMALS};
use crate::error::InputError;
use crate::plugin;
use crate::util::Result;
use crate::xml::{Kind, Object};
use tessera_core::geometry::{Disk, ShapeKind};

/// Every `<shape type=...>` Tessera knows.
pub static SHAPES: &[ShapePlugin] = &[
    SPHERE,
    OBJ,
    PLY,
    SERIALIZED,
    RECTANGLE,
    CUBE,
    DISK,
    cylinder::CYLINDER,
    curve::LINEARCURVE,
    curve::BSPLINECURVE,
    instancing::SHAPEGROUP,
    instancing::INSTANCE,
];

/// A shape's geometry and what is attached to it, before indices are assigned.
pub struct ShapeParts<'a> {
    /// The plugin, to report the object's unused parameters once its children are built.
    pub plugin: &'static ShapePlugin,
    /// The geometry that takes the shape's `<bsdf>` and `<emitter>` (none when every face of an
    /// OBJ has an MTL material).
    pub kind: Option<ShapeKind>,
    /// The OBJ's faces with MTL materials (`use_mtl`).
    pub mtl_parts: Vec<MtlPart>,
    pub disk: Option<Disk>,
    pub flip_normals: bool,
    pub bsdf: Option<&'a crate::xml::Child>,
    pub emitter: Option<&'a crate::xml::Child>,
    /// The mesh file gave Mitsuba mesh attributes (see `Geometry::mesh_attributes`).
    pub mesh_attributes: bool,
}

/// Builds the geometry of a shape object and finds its bsdf / emitter children. The caller
/// reports unused parameters (`ShapeParts::plugin`) once it has built the children.
pub(crate) fn build_shape(obj: &Object) -> Result<ShapeParts<'_>> {
    let flip_normals = FLIP_NORMALS.read_bool(obj)?;
    let plugin = plugin::find(SHAPES, "shape", obj)?;
    let Geometry {
        kind,
        disk,
        mtl_parts,
        mesh_attributes,
    } = (plugin.build)(obj)?;
    let mut bsdf = None;
    let mut emitter = None;
    for c in &obj.children {
        let slot = match c.obj.kind {
            Kind::Bsdf => &mut bsdf,
            Kind::Emitter => &mut emitter,
            _ => continue,
        };
        if slot.is_some() {
            return Err(InputError::at(
                &c.loc,
                format!("{} has more than one {}", obj.describe(), c.obj.kind),
            ));
        }
        if kind.is_none() {
            return Err(InputError::at(
                &c.loc,
                format!(
                    "every face of {} has an MTL material (use_mtl), so its {} would apply to \
                     nothing",
                    obj.describe(),
                    c.obj.kind
                ),
            ));
        }
        if c.obj.kind == Kind::Emitter && matches!(kind, Some(ShapeKind::Curve(_))) {
            return Err(InputError::at(
                &c.loc,
                format!(
                    "an emitter on {}: curves cannot emit light (Mitsuba 3 cannot sample \
                     points on them either)",
                    obj.describe()
                ),
            ));
        }
        c.mark_used();
        *slot = Some(c);
    }
    // Mitsuba 3's curves ignore flip_normals (declared ignored: a located warning).
    let flip_normals = flip_normals && !matches!(kind, Some(ShapeKind::Curve(_)));
    Ok(ShapeParts {
        plugin,
        kind,
        mtl_parts,
        disk,
        flip_normals,
        bsdf,
        emitter,
        mesh_attributes,
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn declarations_match_what_the_builders_read() {
        let root = env!("CARGO_MANIFEST_DIR");
        crate::plugin::check::check_family(
            super::SHAPES,
            crate::xml::Kind::Shape,
            |obj| {
                let p = super::build_shape(obj)?;
                let summary = (p.kind, p.disk, p.flip_normals, p.mtl_parts.len());
                Ok(format!("{summary:?}"))
            },
            |name| match name {
                "obj" => format!(
                    "<string name=\"filename\" value=\"{root}/../scenes/meshes/cbox_light.obj\"/>"
                ),
                "ply" => format!(
                    "<string name=\"filename\" \
                     value=\"{root}/../fuzz/corpus/ply/ascii_normals_uv.ply\"/>"
                ),
                "serialized" => format!(
                    "<string name=\"filename\" \
                     value=\"{root}/../tests/real/mitsuba-data/rectangle_normals_uv.serialized\"/>"
                ),
                "linearcurve" | "bsplinecurve" => format!(
                    "<string name=\"filename\" value=\"{root}/../tests/curve_cases/wave.txt\"/>"
                ),
                _ => String::new(),
            },
            &[],
        );
    }
}

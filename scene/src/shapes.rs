//! The `<shape>` plugins ([`SHAPES`]): geometry to world space, plus the attached BSDF and area
//! emitter. Every shape takes `to_world` and `flip_normals`, an optional `<bsdf>` (nested or
//! `<ref>`; default diffuse 0.5, or black diffuse on an emitting shape, as in Mitsuba 3) and an
//! optional `<emitter type="area">`.
use crate::error::InputError;
use crate::mesh::{self, MeshData, MtlBsdf};
use crate::plugin::{self, Default, Param, ParamType, Plugin, Range};
use crate::util::{at_prop, vec3, Result};
use crate::xml::{Kind, Object};
use glam::{Vec2, Vec3};
use tessera_core::geometry::{Disk, Mesh, ShapeKind, Sphere};
use tessera_core::math::{Norm, Transform};

/// A shape's geometry before the scene gives it indices.
pub struct Geometry {
    /// The geometry that takes the shape's `<bsdf>` and `<emitter>` (none when every face of an
    /// OBJ has an MTL material).
    pub kind: Option<ShapeKind>,
    /// A disk's frame (its `ShapeKind::Disk` index is assigned by the scene builder).
    pub disk: Option<Disk>,
    /// The OBJ's faces with MTL materials (`use_mtl`).
    pub mtl_parts: Vec<MtlPart>,
}

impl Geometry {
    /// No geometry of its own (`shapegroup`, `instance`: the scene builder handles them).
    pub fn none() -> Geometry {
        Geometry {
            kind: None,
            disk: None,
            mtl_parts: Vec::new(),
        }
    }

    pub(crate) fn of(kind: ShapeKind) -> Result<Geometry> {
        Ok(Geometry {
            kind: Some(kind),
            disk: None,
            mtl_parts: Vec::new(),
        })
    }
}

/// A shape plugin.
pub type ShapePlugin = Plugin<fn(&Object) -> Result<Geometry>>;

/// Every `<shape type=...>` Tessera knows.
pub static SHAPES: &[ShapePlugin] = &[
    SPHERE,
    OBJ,
    PLY,
    SERIALIZED,
    RECTANGLE,
    CUBE,
    DISK,
    crate::cylinder::CYLINDER,
    crate::instancing::SHAPEGROUP,
    crate::instancing::INSTANCE,
];

pub(crate) const TO_WORLD: Param = Param::transform("to_world", "object to world");
pub(crate) const FLIP_NORMALS: Param = Param::boolean(
    "flip_normals",
    false,
    "swap the front and back sides (which side an area light or a one-sided BSDF faces)",
);

const CENTER: Param = Param::new(
    "center",
    ParamType::Point,
    Default::Note("(0, 0, 0)"),
    Range::Any,
    "centre, before to_world",
);
pub(crate) const RADIUS: Param =
    Param::float("radius", 1.0, Range::Positive, "radius, before to_world");

/// `sphere`.
pub const SPHERE: ShapePlugin = Plugin {
    name: "sphere",
    aliases: &[],
    doc: "An analytic sphere, placed by to_world * translate(center) * scale(radius) as in \
          Mitsuba 3; to_world must be a similarity (a uniform scale, a rotation, a translation).",
    params: &[CENTER, RADIUS, TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: build_sphere,
};

fn build_sphere(obj: &Object) -> Result<Geometry> {
    let center = vec3(obj.point(CENTER.name, [0.0; 3])?);
    let radius = RADIUS.read_f32(obj)?;
    let tf = TO_WORLD.read_transform(obj)?;
    let c = tf.point(center);
    let axes = [tf.vector(Vec3::X), tf.vector(Vec3::Y), tf.vector(Vec3::Z)].map(|a| a.norm());
    let s = axes[0];
    if axes.iter().any(|a| (a - s).abs() > 1e-4 * s)
        || (tf.vector(Vec3::X).dot(tf.vector(Vec3::Y))).abs() > 1e-4 * s * s
    {
        return Err(
            obj.error("the to_world of a sphere must be a uniform scale, rotation and translation")
        );
    }
    let r = radius * s;
    if !(r > 0.0 && r.is_finite() && c.is_finite()) {
        return Err(obj.error("the sphere's size or position is out of range"));
    }
    Geometry::of(ShapeKind::Sphere(Sphere {
        center: c,
        radius: r,
    }))
}

const FILENAME: Param = Param::file("relative to the scene file", "the mesh file");
const FACE_NORMALS: Param = Param::boolean(
    "face_normals",
    false,
    "use flat face normals, ignoring the file's vertex normals",
);
const USE_MTL: Param = Param::boolean(
    "use_mtl",
    false,
    "apply the file's MTL materials (a Tessera extension; Mitsuba 3 ignores MTL files)",
);

/// `obj`.
pub const OBJ: ShapePlugin = Plugin {
    name: "obj",
    aliases: &[],
    doc: "A Wavefront OBJ triangle mesh. With use_mtl, the mesh is split into one shape per \
          `usemtl` material, each with the BSDF and `Ke` area light the material maps to; faces \
          before any `usemtl` form one more shape with the shape's `<bsdf>` and `<emitter>` \
          (which are then an error if there are no such faces).",
    params: &[FILENAME, FACE_NORMALS, USE_MTL, TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: build_mesh_file,
};

/// `ply`.
pub const PLY: ShapePlugin = Plugin {
    name: "ply",
    aliases: &[],
    doc: "A PLY triangle mesh (ASCII or binary).",
    params: &[FILENAME, FACE_NORMALS, TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: build_mesh_file,
};

const SHAPE_INDEX: Param = Param::integer(
    "shape_index",
    0,
    Range::NonNegative,
    "which mesh of the file to load (a file may hold several; 0 is the first)",
);

/// `serialized`.
pub const SERIALIZED: ShapePlugin = Plugin {
    name: "serialized",
    aliases: &[],
    doc: "A mesh of a Mitsuba `.serialized` file (zlib-compressed, format versions 3 and 4, as \
          Mitsuba 0.x writes them). Vertex colours in the file are skipped, and so is its \
          face-normal flag, as in Mitsuba 3: face_normals decides.",
    params: &[FILENAME, SHAPE_INDEX, FACE_NORMALS, TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: build_mesh_file,
};

fn build_mesh_file(obj: &Object) -> Result<Geometry> {
    let name = obj
        .string_opt(FILENAME.name)?
        .ok_or_else(|| obj.error(format!("{} needs \"filename\"", obj.describe())))?;
    let path = obj.resolve_file(&name);
    let use_mtl = obj.plugin == OBJ.name && USE_MTL.read_bool(obj)?;
    let face_normals = FACE_NORMALS.read_bool(obj)?;
    let tf = TO_WORLD.read_transform(obj)?;
    if !use_mtl {
        let data = if obj.plugin == OBJ.name {
            mesh::load_obj(&path)
        } else if obj.plugin == SERIALIZED.name {
            mesh::load_serialized(&path, SHAPE_INDEX.read_i64(obj)? as u64)
        } else {
            mesh::load_ply(&path)
        }
        .map_err(|e| at_filename(obj, e))?;
        return Geometry::of(ShapeKind::Mesh(to_world_mesh(
            obj,
            data,
            &tf,
            face_normals,
        )?));
    }
    let parts = mesh::load_obj_with_materials(&path).map_err(|e| at_filename(obj, e))?;
    let mut mtl_parts = Vec::new();
    for (i, data) in parts.by_material {
        mtl_parts.push(MtlPart {
            mesh: to_world_mesh(obj, data, &tf, face_normals)?,
            material: mesh::mtl_bsdf(&parts.materials[i])?,
        });
    }
    let kind = match parts.plain {
        Some(data) => Some(ShapeKind::Mesh(to_world_mesh(
            obj,
            data,
            &tf,
            face_normals,
        )?)),
        None => None,
    };
    Ok(Geometry {
        kind,
        disk: None,
        mtl_parts,
    })
}

/// `rectangle`.
pub const RECTANGLE: ShapePlugin = Plugin {
    name: "rectangle",
    aliases: &[],
    doc: "The square [-1, 1]^2 at z = 0, facing +z, placed by to_world.",
    params: &[TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: |obj| unit_mesh(obj, mesh::rectangle()),
};

/// `cube`.
pub const CUBE: ShapePlugin = Plugin {
    name: "cube",
    aliases: &[],
    doc: "The cube [-1, 1]^3, facing out, placed by to_world.",
    params: &[TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: |obj| unit_mesh(obj, mesh::cube()),
};

fn unit_mesh(obj: &Object, data: MeshData) -> Result<Geometry> {
    let tf = TO_WORLD.read_transform(obj)?;
    Geometry::of(ShapeKind::Mesh(to_world_mesh(obj, data, &tf, false)?))
}

/// `disk`.
pub const DISK: ShapePlugin = Plugin {
    name: "disk",
    aliases: &[],
    doc: "The unit disk at z = 0, facing +z, placed by to_world (an analytic shape).",
    params: &[TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: |obj| {
        let tf = TO_WORLD.read_transform(obj)?;
        let disk = Disk::new(tf).ok_or_else(|| obj.error("the disk's to_world flattens it"))?;
        Ok(Geometry {
            kind: Some(ShapeKind::Disk(0)),
            disk: Some(disk),
            mtl_parts: Vec::new(),
        })
    },
};

/// A part of an OBJ mesh with its MTL material.
pub struct MtlPart {
    /// The faces of the material, in world space.
    pub mesh: Mesh,
    /// The material's BSDF and emission.
    pub material: MtlBsdf,
}

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
}

/// A mesh error with no line in the mesh file (unreadable, too large, bad header...) is
/// reported at the scene's `filename` property, still naming the mesh file.
fn at_filename(obj: &Object, e: InputError) -> InputError {
    if e.loc.is_some() {
        return e;
    }
    match &e.file {
        Some(f) => at_prop(obj, "filename", format!("{}: {}", f.display(), e.msg)),
        None => at_prop(obj, "filename", e.msg),
    }
}

fn to_world_mesh(obj: &Object, data: MeshData, tf: &Transform, face_normals: bool) -> Result<Mesh> {
    let mut data = data;
    if face_normals {
        data.normals.clear();
    } else if data.normals.is_empty() {
        data.compute_vertex_normals();
    }
    let positions: Vec<Vec3> = data
        .positions
        .iter()
        .map(|p| tf.point(Vec3::from(*p)))
        .collect();
    if positions.iter().any(|p| !p.is_finite()) {
        return Err(obj.error("the mesh leaves single-precision range after to_world"));
    }
    let normals = data
        .normals
        .iter()
        .map(|n| tf.normal(Vec3::from(*n)).unit_or_zero())
        .collect();
    let uvs = data.uvs.iter().map(|u| Vec2::from(*u)).collect();
    Ok(Mesh::new(positions, normals, uvs, data.indices))
}

/// Builds the geometry of a shape object and finds its bsdf / emitter children. The caller
/// reports unused parameters (`ShapeParts::plugin`) once it has built the children.
pub fn build_shape(obj: &Object) -> Result<ShapeParts<'_>> {
    let flip_normals = FLIP_NORMALS.read_bool(obj)?;
    let plugin = plugin::find(SHAPES, "shape", obj)?;
    let Geometry {
        kind,
        disk,
        mtl_parts,
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
        c.mark_used();
        *slot = Some(c);
    }
    Ok(ShapeParts {
        plugin,
        kind,
        mtl_parts,
        disk,
        flip_normals,
        bsdf,
        emitter,
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
                _ => String::new(),
            },
            &[],
        );
    }
}

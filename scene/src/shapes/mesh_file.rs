//! The mesh-file shapes, `obj`, `ply` and `serialized`: a mesh read from a file and carried to
//! world space.
use super::{Geometry, MtlPart, ShapePlugin, FLIP_NORMALS, TO_WORLD};
use crate::error::InputError;
use crate::mesh::{self, MeshData};
use crate::plugin::{Param, Plugin, Range};
use crate::util::{at_prop, Result};
use crate::xml::Object;
use glam::{Vec2, Vec3};
use tessera_core::geometry::{Mesh, ShapeKind};
use tessera_core::math::{Norm, Transform};

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
    doc: "A PLY triangle mesh (ASCII or binary). Polygons are fan-triangulated; the vertex \
          and face properties beyond positions, normals, uv and indices become mesh \
          attributes named as Mitsuba 3 names them (`vertex_color`, `face_weight`, ...), which \
          `mesh_attribute` textures read.",
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
pub(crate) const SERIALIZED: ShapePlugin = Plugin {
    name: "serialized",
    aliases: &[],
    doc: "A mesh of a Mitsuba `.serialized` file (zlib-compressed, format versions 3 and 4, as \
          Mitsuba 0.x writes them). Vertex colours in the file are skipped, and so is its \
          face-normal flag, as in Mitsuba 3: face_normals decides.",
    params: &[FILENAME, SHAPE_INDEX, FACE_NORMALS, TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: build_mesh_file,
};

/// What a mesh-file shape reads: the file, whether its MTL materials split it (`obj` only) and
/// which mesh of the file (`serialized` only; 0 for the others).
struct MeshRead {
    path: std::path::PathBuf,
    use_mtl: bool,
    index: u64,
}

fn mesh_read(obj: &Object) -> Result<MeshRead> {
    let name = obj
        .string_opt(FILENAME.name)?
        .ok_or_else(|| obj.error(format!("{} needs \"filename\"", obj.describe())))?;
    Ok(MeshRead {
        path: obj.resolve_file(&name),
        use_mtl: obj.plugin == OBJ.name && USE_MTL.read_bool(obj)?,
        index: match obj.plugin == SERIALIZED.name {
            true => SHAPE_INDEX.read_i64(obj)? as u64,
            false => 0,
        },
    })
}

fn build_mesh_file(obj: &Object) -> Result<Geometry> {
    let MeshRead {
        path,
        use_mtl,
        index,
    } = mesh_read(obj)?;
    let face_normals = FACE_NORMALS.read_bool(obj)?;
    let tf = TO_WORLD.read_transform(obj)?;
    if !use_mtl {
        let key = read_key(obj, &path, index);
        let data = mesh::read_shared(key, || {
            if obj.plugin == OBJ.name {
                mesh::load_obj(&path)
            } else if obj.plugin == SERIALIZED.name {
                mesh::load_serialized(&path, index)
            } else {
                mesh::load_ply(&path)
            }
        })
        .map_err(|e| at_filename(obj, e))?;
        let mesh_attributes = !data.attributes.is_empty();
        let mut g = Geometry::of(ShapeKind::Mesh(to_world_mesh(
            obj,
            data,
            &tf,
            face_normals,
        )?))?;
        g.mesh_attributes = mesh_attributes;
        return Ok(g);
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
        mesh_attributes: false,
    })
}

/// The reader of a mesh-file shape's plugin, as a [`mesh::ReadKey`] names it.
fn reader(plugin: &str) -> Option<&'static str> {
    [OBJ.name, PLY.name, SERIALIZED.name]
        .into_iter()
        .find(|&n| n == plugin)
}

/// What reading the mesh of `obj` (at `path`, mesh `index` of the file) depends on.
fn read_key(obj: &Object, path: &std::path::Path, index: u64) -> Option<mesh::ReadKey> {
    mesh::ReadKey::new(path, reader(&obj.plugin)?, index)
}

/// The mesh files the shapes under `root` will read, each counted once per shape that names
/// it (a shape reached twice through `<ref>`s counts once), so that a file named by several
/// shapes is parsed once (see `mesh/file_cache.rs`). A shape whose parameters are wrong is not
/// counted: building it reports them.
pub(crate) fn plan_mesh_reads(root: &Object) -> mesh::Plan {
    let mut plan = mesh::Plan::default();
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![root];
    while let Some(obj) = stack.pop() {
        if !seen.insert(obj as *const Object) {
            continue;
        }
        stack.extend(obj.children.iter().map(|c| &*c.obj));
        if obj.kind != crate::xml::Kind::Shape || reader(&obj.plugin).is_none() {
            continue;
        }
        let r = mesh_read(obj).ok().filter(|r| !r.use_mtl);
        if let Some(key) = r.and_then(|r| read_key(obj, &r.path, r.index)) {
            plan.count(key);
        }
    }
    plan
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

/// A mesh's data carried to world space by `tf` (vertex normals computed when the file has none
/// and `face_normals` is off).
pub(crate) fn to_world_mesh(
    obj: &Object,
    data: MeshData,
    tf: &Transform,
    face_normals: bool,
) -> Result<Mesh> {
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
    let mut mesh = Mesh::new(positions, normals, uvs, data.indices);
    mesh.attributes = data.attributes;
    Ok(mesh)
}

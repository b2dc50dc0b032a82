//! `<shape>` objects: geometry to world space, plus the attached BSDF and area emitter.
//!
//! `sphere`: `center` (point, 0), `radius` (float > 0, 1), `to_world` (a similarity; applied as
//! to_world * translate(center) * scale(radius), as Mitsuba 3 does). `obj`, `ply`: `filename`
//! (relative to the scene file), `face_normals` (false). `rectangle`, `cube`, `disk`: unit shapes
//! placed by `to_world`. Every shape: `to_world`, `flip_normals` (false), an optional `<bsdf>`
//! (nested or `<ref>`; default diffuse 0.5, or black diffuse on an emitting shape, as in Mitsuba
//! 3), an optional `<emitter type="area">`.
//!
//! `obj` only: `use_mtl` (boolean, default false; a Tessera extension, Mitsuba 3 ignores MTL
//! files). When true, the file's `mtllib` materials apply: the mesh is split into one shape per
//! `usemtl` material, each with the BSDF and `Ke` area light that `mesh/mtl_material.rs` maps
//! the material to; faces before any `usemtl` form one more shape with the shape's `<bsdf>` and
//! `<emitter>` (which are then an error if there are no such faces).
use super::util::{at_prop, float_checked, transform, vec3, Result};
use crate::error::InputError;
use crate::mesh::{self, MeshData, MtlBsdf};
use crate::xml::{Kind, Object};
use glam::{Vec2, Vec3};
use tessera_core::geometry::{Disk, Mesh, ShapeKind, Sphere};
use tessera_core::math::{Norm, Transform};

/// A part of an OBJ mesh with its MTL material.
pub struct MtlPart {
    /// The faces of the material, in world space.
    pub mesh: Mesh,
    /// The material's BSDF and emission.
    pub material: MtlBsdf,
}

/// A shape's geometry and what is attached to it, before indices are assigned.
pub struct ShapeParts<'a> {
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

/// Builds the geometry of a shape object and finds its bsdf / emitter children.
pub fn build_shape(obj: &Object) -> Result<ShapeParts<'_>> {
    let flip_normals = obj.boolean("flip_normals", false)?;
    let mut disk = None;
    let mut mtl_parts = Vec::new();
    let kind = match obj.plugin.as_str() {
        "sphere" => {
            let center = vec3(obj.point("center", [0.0; 3])?);
            let radius = float_checked(obj, "radius", 1.0, |r| r > 0.0, "positive")?;
            let tf = transform(obj, "to_world")?;
            let c = tf.point(center);
            let axes =
                [tf.vector(Vec3::X), tf.vector(Vec3::Y), tf.vector(Vec3::Z)].map(|a| a.norm());
            let s = axes[0];
            if axes.iter().any(|a| (a - s).abs() > 1e-4 * s)
                || (tf.vector(Vec3::X).dot(tf.vector(Vec3::Y))).abs() > 1e-4 * s * s
            {
                return Err(obj.error(
                    "the to_world of a sphere must be a uniform scale, rotation and translation",
                ));
            }
            let r = radius * s;
            if !(r > 0.0 && r.is_finite() && c.is_finite()) {
                return Err(obj.error("the sphere's size or position is out of range"));
            }
            Some(ShapeKind::Sphere(Sphere {
                center: c,
                radius: r,
            }))
        }
        "obj" | "ply" => {
            let name = obj
                .string_opt("filename")?
                .ok_or_else(|| obj.error(format!("{} needs \"filename\"", obj.describe())))?;
            let base = obj
                .loc
                .file
                .parent()
                .map(|p| p.to_path_buf())
                .unwrap_or_default();
            let path = base.join(&name);
            let use_mtl = obj.plugin == "obj" && obj.boolean("use_mtl", false)?;
            let face_normals = obj.boolean("face_normals", false)?;
            let tf = transform(obj, "to_world")?;
            if use_mtl {
                let parts =
                    mesh::load_obj_with_materials(&path).map_err(|e| at_filename(obj, e))?;
                for (i, data) in parts.by_material {
                    mtl_parts.push(MtlPart {
                        mesh: to_world_mesh(obj, data, &tf, face_normals)?,
                        material: mesh::mtl_bsdf(&parts.materials[i])?,
                    });
                }
                match parts.plain {
                    Some(data) => Some(ShapeKind::Mesh(to_world_mesh(
                        obj,
                        data,
                        &tf,
                        face_normals,
                    )?)),
                    None => None,
                }
            } else {
                let data = if obj.plugin == "obj" {
                    mesh::load_obj(&path)
                } else {
                    mesh::load_ply(&path)
                }
                .map_err(|e| at_filename(obj, e))?;
                Some(ShapeKind::Mesh(to_world_mesh(
                    obj,
                    data,
                    &tf,
                    face_normals,
                )?))
            }
        }
        "rectangle" | "cube" => {
            let data = if obj.plugin == "cube" {
                mesh::cube()
            } else {
                mesh::rectangle()
            };
            let tf = transform(obj, "to_world")?;
            Some(ShapeKind::Mesh(to_world_mesh(obj, data, &tf, false)?))
        }
        "disk" => {
            let tf = transform(obj, "to_world")?;
            disk = Some(Disk::new(tf).ok_or_else(|| obj.error("the disk's to_world flattens it"))?);
            Some(ShapeKind::Disk(0))
        }
        other => {
            return Err(obj.error(format!(
                "unknown shape \"{other}\" (known: sphere, obj, ply, rectangle, disk, cube)"
            )));
        }
    };
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
        kind,
        mtl_parts,
        disk,
        flip_normals,
        bsdf,
        emitter,
    })
}

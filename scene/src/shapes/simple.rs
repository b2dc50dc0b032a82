//! The simple shapes: the analytic `sphere` and `disk`, and the unit meshes `rectangle` and
//! `cube`.
use super::mesh_file::to_world_mesh;
use super::{Geometry, ShapePlugin, FLIP_NORMALS, RADIUS, TO_WORLD};
use crate::mesh::{self, MeshData};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::{vec3, Result};
use crate::xml::Object;
use glam::Vec3;
use tessera_core::geometry::{Disk, ShapeKind, Sphere};
use tessera_core::math::Norm;

const CENTER: Param = Param::new(
    "center",
    ParamType::Point,
    Default::Note("(0, 0, 0)"),
    Range::Any,
    "centre, before to_world",
);

/// `sphere`.
pub(crate) const SPHERE: ShapePlugin = Plugin {
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

/// `rectangle`.
pub(crate) const RECTANGLE: ShapePlugin = Plugin {
    name: "rectangle",
    aliases: &[],
    doc: "The square [-1, 1]^2 at z = 0, facing +z, placed by to_world.",
    params: &[TO_WORLD, FLIP_NORMALS],
    nested: "an optional `<bsdf>` and `<emitter type=\"area\">`",
    build: |obj| unit_mesh(obj, mesh::rectangle()),
};

/// `cube`.
pub(crate) const CUBE: ShapePlugin = Plugin {
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
pub(crate) const DISK: ShapePlugin = Plugin {
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
            mesh_attributes: false,
        })
    },
};

//! The `<shape>` plugins (`SHAPES`, in `table.rs`): geometry to world space, plus the attached
//! BSDF and area emitter. Every shape takes `to_world` and `flip_normals`, an optional `<bsdf>`
//! (nested or `<ref>`; default diffuse 0.5, or black diffuse on an emitting shape, as in
//! Mitsuba 3) and an optional `<emitter type="area">`. This file holds what every shape's file
//! shares: the builder's result and the common parameters.
mod curve;
pub(crate) mod cylinder;
pub(crate) mod instancing;
mod mesh_file;
mod simple;
mod table;

pub(crate) use mesh_file::plan_mesh_reads;
pub(crate) use table::build_shape;
pub use table::SHAPES;

use crate::mesh::MtlBsdf;
use crate::plugin::{Param, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::geometry::{Disk, Mesh, ShapeKind};

/// A shape's geometry before the scene gives it indices.
pub struct Geometry {
    /// The geometry that takes the shape's `<bsdf>` and `<emitter>` (none when every face of an
    /// OBJ has an MTL material).
    pub kind: Option<ShapeKind>,
    /// A disk's frame (its `ShapeKind::Disk` index is assigned by the scene builder).
    pub disk: Option<Disk>,
    /// The OBJ's faces with MTL materials (`use_mtl`).
    pub mtl_parts: Vec<MtlPart>,
    /// The mesh file gave mesh attributes in Mitsuba 3's sense (a PLY's extra properties),
    /// which decides how Mitsuba lists the shape (`crate::shape_numbering`).
    pub mesh_attributes: bool,
}

impl Geometry {
    /// No geometry of its own (`shapegroup`, `instance`: the scene builder handles them).
    pub fn none() -> Geometry {
        Geometry {
            kind: None,
            disk: None,
            mtl_parts: Vec::new(),
            mesh_attributes: false,
        }
    }

    pub(crate) fn of(kind: ShapeKind) -> Result<Geometry> {
        Ok(Geometry {
            kind: Some(kind),
            disk: None,
            mtl_parts: Vec::new(),
            mesh_attributes: false,
        })
    }
}

/// A shape plugin.
pub(crate) type ShapePlugin = Plugin<fn(&Object) -> Result<Geometry>>;

/// A part of an OBJ mesh with its MTL material.
pub(crate) struct MtlPart {
    /// The faces of the material, in world space.
    pub mesh: Mesh,
    /// The material's BSDF and emission.
    pub material: MtlBsdf,
}

pub(crate) const TO_WORLD: Param = Param::transform("to_world", "object to world");
pub(crate) const FLIP_NORMALS: Param = Param::boolean(
    "flip_normals",
    false,
    "swap the front and back sides (which side an area light or a one-sided BSDF faces)",
);

pub(crate) const RADIUS: Param =
    Param::float("radius", 1.0, Range::Positive, "radius, before to_world");

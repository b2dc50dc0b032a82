//! Mitsuba 3.9.1's numbering of a scene's shapes, which the `aov` integrator's `shape_index` and
//! `prim_index` outputs give; the loader computes it (`scene/src/shape_numbering.rs` says how
//! Mitsuba lists shapes) and the scene keeps it.
use alloc::vec::Vec;

/// How one shape is numbered in Mitsuba 3.9.1's `scene.shapes()` (see [`ShapeNumbering`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShapeNumber {
    /// Its 1-based position in Mitsuba's shape list (the `shape_index` output).
    pub index: u32,
    /// What Mitsuba adds to its triangle indices: the triangles of the meshes merged before it
    /// into the same Mitsuba mesh.
    pub prim_offset: u32,
    /// Mitsuba's `rectangle`: its two triangles are split along the other diagonal than
    /// Tessera's, so its triangle index is found from the texture coordinates.
    pub rectangle: bool,
}

/// Mitsuba 3.9.1's numbering of the scene's shapes, set by the loader. Empty (the default):
/// shape `i` is number `i + 1`, instance `j` follows all shapes, no offsets.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ShapeNumbering {
    /// One per shape of the scene, by shape index.
    pub shapes: Vec<ShapeNumber>,
    /// One per instance (its 1-based position in Mitsuba's shape list).
    pub instances: Vec<u32>,
}

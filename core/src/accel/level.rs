//! One level of the scene's hierarchy built from a list of shapes: their primitives in BVH
//! order, the triangle blocks and the 8-wide BVH over them. The scene's top level (every shape
//! outside a shape group, then one primitive per instance) and each shape group's bottom level
//! are built by the same steps, so a scene without instances builds exactly as before.
use super::{BuildParams, Bvh8, Collapse, Fork, TriBlocks};
use crate::geometry::{Disk, Prim, Shape, ShapeKind};
use crate::math::Aabb;
use alloc::vec::Vec;
use glam::Vec3;

/// The corners stored for a primitive that is not a triangle.
pub(crate) const NOT_A_TRIANGLE: [Vec3; 3] = [Vec3::NAN; 3];

/// Why a level could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LevelError {
    /// A disk index out of range.
    BadIndex,
    /// A mesh index out of range.
    BadMeshIndex,
    /// Too many primitives for 32-bit ids.
    TooLarge,
}

/// Primitives of a level before ordering: each with its triangle corners (NaN for others).
#[derive(Default)]
pub struct LevelPrims {
    /// Primitives in input order.
    pub prims: Vec<Prim>,
    /// Their corners.
    pub tris: Vec<[Vec3; 3]>,
}

impl LevelPrims {
    /// The primitives of shapes `which` of `shapes`, in that order, in arrays sized for them
    /// first (growing them push by push copied a 325k-triangle scene's several times).
    pub(crate) fn of_shapes(
        shapes: &[Shape],
        which: impl Iterator<Item = usize> + Clone,
        disks: &[Disk],
    ) -> Result<Self, LevelError> {
        let n = which
            .clone()
            .filter_map(|si| shapes.get(si))
            .map(prim_count)
            .sum();
        let mut level = LevelPrims {
            prims: Vec::with_capacity(n),
            tris: Vec::with_capacity(n),
        };
        for si in which {
            level.push_shape(si, shapes.get(si).ok_or(LevelError::BadIndex)?, disks)?;
        }
        Ok(level)
    }

    /// Appends the primitives of shape `si` (as many as [`prim_count`] says).
    fn push_shape(&mut self, si: usize, s: &Shape, disks: &[Disk]) -> Result<(), LevelError> {
        let shape = u32::try_from(si).map_err(|_| LevelError::TooLarge)?;
        match &s.kind {
            ShapeKind::Mesh(m) => {
                let n = m.positions.len();
                for (f, idx) in m.indices.iter().enumerate() {
                    if idx.iter().any(|&i| i as usize >= n) {
                        return Err(LevelError::BadMeshIndex);
                    }
                    let face = u32::try_from(f).map_err(|_| LevelError::TooLarge)?;
                    self.prims.push(Prim::Triangle { shape, face });
                    self.tris.push(m.vertices(f));
                }
            }
            ShapeKind::Sphere(sp) => {
                self.prims.push(Prim::Sphere { sphere: *sp, shape });
                self.tris.push(NOT_A_TRIANGLE);
            }
            ShapeKind::Disk(d) => {
                if *d as usize >= disks.len() {
                    return Err(LevelError::BadIndex);
                }
                self.prims.push(Prim::Disk { disk: *d, shape });
                self.tris.push(NOT_A_TRIANGLE);
            }
            ShapeKind::Cylinder(_) => {
                self.prims.push(Prim::Cylinder { shape });
                self.tris.push(NOT_A_TRIANGLE);
            }
            ShapeKind::Curve(c) => {
                for seg in 0..c.segment_count() {
                    let segment = u32::try_from(seg).map_err(|_| LevelError::TooLarge)?;
                    self.prims.push(Prim::Curve { shape, segment });
                    self.tris.push(NOT_A_TRIANGLE);
                }
            }
        }
        Ok(())
    }
}

/// How many primitives shape `s` adds to a level: a triangle per mesh face, a segment per
/// curve segment, one for any other shape.
fn prim_count(s: &Shape) -> usize {
    match &s.kind {
        ShapeKind::Mesh(m) => m.indices.len(),
        ShapeKind::Curve(c) => c.segment_count(),
        _ => 1,
    }
}

/// A built level: primitives in BVH order, their triangle blocks and the hierarchy.
#[derive(Clone, Debug)]
pub struct Level {
    /// Primitives in BVH order.
    pub prims: Vec<Prim>,
    /// Triangle corners in blocks of four (see `Scene::blocks`).
    pub blocks: TriBlocks,
    /// The 8-wide hierarchy over `prims`.
    pub bvh: Bvh8,
}

impl Level {
    /// Orders `lp` by a BVH over `bounds` (one box per primitive) and packs the blocks; the
    /// build's large halves go through `fork` (the same level whatever it does).
    pub fn build(lp: LevelPrims, bounds: &[Aabb], params: BuildParams, fork: &dyn Fork) -> Level {
        let (mut bvh, order) = Bvh8::build_forked(bounds, params, Collapse::DEFAULT, fork);
        let prims: Vec<Prim> = order.iter().map(|&i| lp.prims[i as usize]).collect();
        let tris: Vec<[Vec3; 3]> = order.iter().map(|&i| lp.tris[i as usize]).collect();
        let blocks = TriBlocks::build(&mut bvh, &tris);
        Level { prims, blocks, bvh }
    }

    /// Bytes of its ray-casting data.
    pub fn memory_bytes(&self) -> usize {
        self.bvh.memory_bytes()
            + self.blocks.memory_bytes()
            + core::mem::size_of_val(self.prims.as_slice())
    }
}

//! Volumes: quantities that vary through space (a heterogeneous medium's extinction and albedo),
//! Mitsuba 3's `<volume>` plugins `constvolume` and `gridvolume`.
//!
//! Each has a local space whose unit cube `[0, 1]^3` is its extent; `to_world` places it. That
//! cube, transformed, is where a heterogeneous medium whose `sigma_t` this is has any extinction
//! (as in Mitsuba 3, also for a constant: its cube is the unit cube unless `to_world` moves it).
use super::sggx::SggxMatrix;
use super::voxel_grid::{GridFilter, GridWrap, VoxelGrid};
use crate::math::Transform;
use crate::Color;
use glam::Vec3;

/// A voxel grid with its lookup settings (`gridvolume`).
#[derive(Clone, Debug)]
pub struct GridVolume {
    /// The voxels.
    pub grid: VoxelGrid,
    /// Blend between voxel centres or not.
    pub filter: GridFilter,
    /// Lookups outside the cube.
    pub wrap: GridWrap,
}

/// What a volume holds.
#[derive(Clone, Debug)]
pub enum VolumeData {
    /// The same value everywhere (`constvolume`, or a float or rgb given directly).
    Constant(Color),
    /// A voxel grid (`gridvolume`).
    Grid(GridVolume),
}

/// A volume and where it sits.
#[derive(Clone, Debug)]
pub struct Volume {
    /// Its values.
    pub data: VolumeData,
    /// Local (unit cube) to world.
    pub to_world: Transform,
}

impl Volume {
    /// A constant over the unit cube.
    pub fn constant(c: Color) -> Self {
        Volume {
            data: VolumeData::Constant(c),
            to_world: Transform::IDENTITY,
        }
    }
    /// The value at world point `p`.
    #[inline]
    pub fn eval(&self, p: Vec3) -> Color {
        match &self.data {
            VolumeData::Constant(c) => *c,
            VolumeData::Grid(g) => {
                g.grid
                    .lookup(self.to_world.inv.transform_point3(p), g.filter, g.wrap)
            }
        }
    }
    /// The matrix at world point `p` of a 6-channel grid (an SGGX phase function's `S`); the
    /// identity for a constant, which the loader never builds for `S`.
    #[inline]
    pub fn eval_matrix(&self, p: Vec3) -> SggxMatrix {
        match &self.data {
            VolumeData::Constant(_) => SggxMatrix {
                diag: Vec3::ONE,
                off: Vec3::ZERO,
            },
            VolumeData::Grid(g) => {
                g.grid
                    .lookup_matrix(self.to_world.inv.transform_point3(p), g.filter, g.wrap)
            }
        }
    }
    /// The largest value anywhere, over the channels.
    pub fn max_value(&self) -> f32 {
        match &self.data {
            VolumeData::Constant(c) => c.max_element(),
            VolumeData::Grid(g) => g.grid.max_value(),
        }
    }
}

//! A voxel grid of one, three or six channels (the data of Mitsuba 3's `gridvolume`; six are an
//! SGGX matrix per voxel) and its lookup,
//! as Mitsuba 3.9.1 performs it: the grid fills the unit cube of its local space, voxel `i` of an
//! axis of `n` voxels is centred at `(i + 0.5) / n`, and a lookup outside the cube or between
//! centres first maps voxel indices by the wrap mode.
//!
//! - `Trilinear`: at local coordinate `u`, the axis position `x = u n - 0.5` lies between voxels
//!   `floor(x)` and `floor(x) + 1`, weighted by the fraction; the 8 voxels around the point are
//!   blended.
//! - `Nearest`: the voxel `floor(u n)`.
//!
//! Wrap modes map an index `i` of an axis of `n` voxels into `[0, n)`: `Clamp` to the nearest
//! end, `Repeat` modulo `n`, `Mirror` reflected at each end (period `2 n`).
use super::sggx::SggxMatrix;
use crate::Color;
use alloc::vec::Vec;
use core::ops::{Add, Mul};
use glam::Vec3;

/// How values between voxel centres are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GridFilter {
    /// Blend of the 8 surrounding voxel centres.
    Trilinear,
    /// The voxel containing the point.
    Nearest,
}

/// How indices beyond the grid's ends map into it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GridWrap {
    /// The nearest end voxel.
    Clamp,
    /// The grid tiles space.
    Repeat,
    /// The grid is reflected at its ends.
    Mirror,
}

impl GridWrap {
    /// Index `i` of an axis of `n` voxels mapped into `[0, n)`.
    #[inline]
    pub fn index(self, i: i64, n: u32) -> usize {
        let n = n as i64;
        let j = match self {
            GridWrap::Clamp => i.clamp(0, n - 1),
            GridWrap::Repeat => i.rem_euclid(n),
            GridWrap::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m >= n {
                    2 * n - 1 - m
                } else {
                    m
                }
            }
        };
        j as usize
    }
}

/// Voxel values, x fastest, then y, then z; one, three or six channels per voxel.
#[derive(Clone, Debug)]
pub struct VoxelGrid {
    res: [u32; 3],
    channels: u32,
    data: Vec<f32>,
}

impl VoxelGrid {
    /// A grid of `res` voxels with `channels` (1, 3 or 6) values each; `None` when the data's
    /// length does not match, a resolution is zero, or a value is not finite, or negative in a
    /// grid of 1 or 3 channels (6 hold symmetric matrices, whose off-diagonal may be negative).
    pub fn new(res: [u32; 3], channels: u32, data: Vec<f32>) -> Option<Self> {
        let n = res
            .iter()
            .try_fold(1usize, |a, &r| a.checked_mul(r as usize))?;
        let ok = res.iter().all(|&r| r > 0)
            && matches!(channels, 1 | 3 | 6)
            && n.checked_mul(channels as usize) == Some(data.len())
            && data
                .iter()
                .all(|v| v.is_finite() && (*v >= 0.0 || channels == 6));
        ok.then_some(VoxelGrid {
            res,
            channels,
            data,
        })
    }
    /// Voxels per axis.
    #[inline]
    pub fn res(&self) -> [u32; 3] {
        self.res
    }
    /// Values per voxel (1, 3 or 6).
    #[inline]
    pub fn channels(&self) -> u32 {
        self.channels
    }
    /// The index of voxel `(x, y, z)` (in range).
    #[inline]
    fn index(&self, x: usize, y: usize, z: usize) -> usize {
        (z * self.res[1] as usize + y) * self.res[0] as usize + x
    }
    /// The value of voxel `(x, y, z)` (in range) of a grid of 1 or 3 channels; a single channel
    /// is grey.
    #[inline]
    pub fn voxel(&self, x: usize, y: usize, z: usize) -> Color {
        let i = self.index(x, y, z);
        if self.channels == 1 {
            Color::splat(self.data[i])
        } else {
            let k = 3 * i;
            Color::new(self.data[k], self.data[k + 1], self.data[k + 2])
        }
    }
    /// The matrix of voxel `(x, y, z)` (in range) of a grid of 6 channels.
    #[inline]
    pub fn voxel_matrix(&self, x: usize, y: usize, z: usize) -> SggxMatrix {
        let k = 6 * self.index(x, y, z);
        let c = &self.data[k..k + 6];
        SggxMatrix::from_channels([c[0], c[1], c[2], c[3], c[4], c[5]])
    }
    /// The largest projected-area bound of any voxel's matrix (6 channels; see
    /// [`SggxMatrix::projected_area_bound`]): a trilinear blend of the matrices stays below it.
    pub fn max_projected_area(&self) -> f32 {
        self.data
            .chunks_exact(6)
            .map(|c| {
                SggxMatrix::from_channels([c[0], c[1], c[2], c[3], c[4], c[5]])
                    .projected_area_bound()
            })
            .fold(0.0, f32::max)
    }
    /// Whether every voxel holds the same values.
    pub fn is_uniform(&self) -> bool {
        let c = self.channels as usize;
        self.data.chunks_exact(c).all(|v| v == &self.data[..c])
    }
    /// The largest value of any voxel and channel.
    pub fn max_value(&self) -> f32 {
        self.data.iter().copied().fold(0.0, f32::max)
    }
    /// The largest value over the voxels whose (unwrapped) indices lie in `lo..=hi` per axis,
    /// each mapped by `wrap`, over every channel.
    pub fn max_in(&self, lo: [i64; 3], hi: [i64; 3], wrap: GridWrap) -> f32 {
        let mut m = 0.0f32;
        for z in lo[2]..=hi[2] {
            let zi = wrap.index(z, self.res[2]);
            for y in lo[1]..=hi[1] {
                let yi = wrap.index(y, self.res[1]);
                for x in lo[0]..=hi[0] {
                    let xi = wrap.index(x, self.res[0]);
                    m = m.max(self.voxel(xi, yi, zi).max_element());
                }
            }
        }
        m
    }
    /// The value at local point `u` (the grid spans the unit cube) of a grid of 1 or 3
    /// channels.
    #[inline]
    pub fn lookup(&self, u: Vec3, filter: GridFilter, wrap: GridWrap) -> Color {
        self.lookup_with(u, filter, wrap, |x, y, z| self.voxel(x, y, z))
    }
    /// The matrix at local point `u` of a grid of 6 channels.
    #[inline]
    pub fn lookup_matrix(&self, u: Vec3, filter: GridFilter, wrap: GridWrap) -> SggxMatrix {
        self.lookup_with(u, filter, wrap, |x, y, z| self.voxel_matrix(x, y, z))
    }
    /// The lookup at local point `u` over voxel values read by `v`.
    #[inline]
    fn lookup_with<T, F>(&self, u: Vec3, filter: GridFilter, wrap: GridWrap, voxel: F) -> T
    where
        T: Copy + Add<Output = T> + Mul<f32, Output = T>,
        F: Fn(usize, usize, usize) -> T,
    {
        let r = self.res;
        match filter {
            GridFilter::Nearest => {
                let i = |a: usize| wrap.index(libm::floorf(u[a] * r[a] as f32) as i64, r[a]);
                voxel(i(0), i(1), i(2))
            }
            GridFilter::Trilinear => {
                let mut idx = [[0usize; 2]; 3];
                let mut w = [0.0f32; 3];
                for a in 0..3 {
                    let x = u[a] * r[a] as f32 - 0.5;
                    let f = libm::floorf(x);
                    w[a] = x - f;
                    idx[a] = [wrap.index(f as i64, r[a]), wrap.index(f as i64 + 1, r[a])];
                }
                let lerp = |a: T, b: T, t: f32| a * (1.0 - t) + b * t;
                let v = |i: usize, j: usize, k: usize| voxel(idx[0][i], idx[1][j], idx[2][k]);
                let c00 = lerp(v(0, 0, 0), v(1, 0, 0), w[0]);
                let c10 = lerp(v(0, 1, 0), v(1, 1, 0), w[0]);
                let c01 = lerp(v(0, 0, 1), v(1, 0, 1), w[0]);
                let c11 = lerp(v(0, 1, 1), v(1, 1, 1), w[0]);
                lerp(lerp(c00, c10, w[1]), lerp(c01, c11, w[1]), w[2])
            }
        }
    }
}

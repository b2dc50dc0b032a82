//! A coarse grid of majorants over a heterogeneous medium's extent: for each of its cells (a
//! block of voxels, "supervoxel"), a bound on the extinction anywhere in it, so that delta and
//! ratio tracking take short steps only where the medium is dense.
//!
//! The bound of a cell is the largest voxel value (over the channels) among every voxel a lookup
//! inside the cell can read: for trilinear lookups the voxels whose centres bracket the cell's
//! span, widened by one voxel on each side against rounding, each index mapped by the wrap mode.
//! A trilinear value is a convex blend of those voxels, so it never exceeds the bound. Mitsuba
//! 3.9.1 uses a single majorant, the grid's maximum; with one cell this grid is that.
//!
//! The grid lives in the local space of the extinction volume (its unit cube); a ray is walked
//! through its cells in that space, where the ray's parameter is the same as in world space.
use super::volume::{Volume, VolumeData};
use super::voxel_grid::GridFilter;
use alloc::vec;
use alloc::vec::Vec;
use glam::Vec3;

/// Relative margin on every bound: a trilinear blend computed in f32 may exceed the largest
/// voxel it blends by an ulp or two.
const MARGIN: f32 = 1.0 + 8.0 * f32::EPSILON;

/// Cells per axis at most.
pub const MAJORANT_CELLS: u32 = 16;

/// Per-cell bounds on the extinction (scale applied), over the unit cube.
#[derive(Clone, Debug)]
pub struct MajorantGrid {
    res: [u32; 3],
    values: Vec<f32>,
}

/// The range of voxel indices (before wrapping) a lookup in `[a, b]` of the unit interval can
/// read, on an axis of `n` voxels, one voxel wider on each side.
fn voxel_span(a: f32, b: f32, n: u32, filter: GridFilter) -> (i64, i64) {
    let n = n as f32;
    match filter {
        GridFilter::Trilinear => (
            libm::floorf(a * n - 0.5) as i64 - 1,
            libm::floorf(b * n - 0.5) as i64 + 2,
        ),
        GridFilter::Nearest => (
            libm::floorf(a * n) as i64 - 1,
            libm::floorf(b * n) as i64 + 1,
        ),
    }
}

impl MajorantGrid {
    /// The majorants of `sigma_t` times `scale`.
    pub fn new(sigma_t: &Volume, scale: f32) -> Self {
        match &sigma_t.data {
            VolumeData::Constant(c) => MajorantGrid {
                res: [1; 3],
                values: vec![c.max_element() * scale * MARGIN],
            },
            VolumeData::Grid(g) => {
                let vres = g.grid.res();
                let res = vres.map(|r| r.min(MAJORANT_CELLS));
                let mut values = Vec::with_capacity((res[0] * res[1] * res[2]) as usize);
                for z in 0..res[2] {
                    for y in 0..res[1] {
                        for x in 0..res[0] {
                            let mut lo = [0i64; 3];
                            let mut hi = [0i64; 3];
                            for (a, i) in [x, y, z].into_iter().enumerate() {
                                let n = res[a] as f32;
                                let (l, h) =
                                    voxel_span(i as f32 / n, (i + 1) as f32 / n, vres[a], g.filter);
                                lo[a] = l;
                                hi[a] = h;
                            }
                            values.push(g.grid.max_in(lo, hi, g.wrap) * scale * MARGIN);
                        }
                    }
                }
                MajorantGrid { res, values }
            }
        }
    }
    /// Cells per axis.
    pub fn res(&self) -> [u32; 3] {
        self.res
    }
    /// The largest majorant (Mitsuba 3.9.1's single majorant).
    pub fn max(&self) -> f32 {
        self.values.iter().copied().fold(0.0, f32::max)
    }
    /// The majorant of cell `(x, y, z)`.
    #[inline]
    pub fn cell(&self, c: [u32; 3]) -> f32 {
        self.values[((c[2] * self.res[1] + c[1]) * self.res[0] + c[0]) as usize]
    }
    /// Walks the local-space ray `o + t d` from `t0` to `t1` (both inside the unit cube)
    /// through the cells, integrating the majorant; returns where that integral reaches `tau`
    /// and the majorant there, or `None` when it does not before `t1`.
    pub fn march(&self, o: Vec3, d: Vec3, t0: f32, t1: f32, tau: f32) -> Option<(f32, f32)> {
        let mut cell = [0u32; 3];
        let mut t_next = [f32::INFINITY; 3];
        let mut dt = [f32::INFINITY; 3];
        let mut step = [0i32; 3];
        let p = o + d * t0;
        for a in 0..3 {
            let n = self.res[a];
            let c = libm::floorf(p[a] * n as f32).clamp(0.0, (n - 1) as f32) as u32;
            cell[a] = c;
            if d[a] > 0.0 {
                step[a] = 1;
                t_next[a] = ((c + 1) as f32 / n as f32 - o[a]) / d[a];
                dt[a] = 1.0 / (n as f32 * d[a]);
            } else if d[a] < 0.0 {
                step[a] = -1;
                t_next[a] = (c as f32 / n as f32 - o[a]) / d[a];
                dt[a] = -1.0 / (n as f32 * d[a]);
            }
        }
        let mut t = t0;
        let mut tau = tau;
        let guard = self.res.iter().sum::<u32>() + 3;
        for _ in 0..guard {
            let a = if t_next[0] <= t_next[1] && t_next[0] <= t_next[2] {
                0
            } else if t_next[1] <= t_next[2] {
                1
            } else {
                2
            };
            let t_exit = t_next[a].min(t1).max(t);
            let m = self.cell(cell);
            if m > 0.0 {
                let need = tau.max(0.0) / m;
                if t + need < t_exit {
                    return Some((t + need, m));
                }
                tau -= m * (t_exit - t);
            }
            t = t_exit;
            if t >= t1 {
                return None;
            }
            let c = cell[a] as i64 + step[a] as i64;
            if c < 0 || c >= self.res[a] as i64 {
                return None;
            }
            cell[a] = c as u32;
            t_next[a] += dt[a];
        }
        None
    }
}

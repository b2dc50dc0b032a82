//! A piecewise-constant 2-D distribution over a grid of cells on the unit square (e.g. the pixels
//! of an environment map), sampled as a marginal over rows then a conditional within the row.
use super::Discrete1D;
use crate::math::next_down;
use alloc::vec::Vec;
use glam::Vec2;

/// Density on `[0,1)^2` that is constant on each of `nx × ny` equal cells, proportional to the
/// cells' weights; built once (scene-build time), then sampled without allocation.
///
/// Row `j` covers `y ∈ [j/ny, (j+1)/ny)`, column `i` covers `x ∈ [i/nx, (i+1)/nx)`. The marginal
/// picks a row by its summed weight, the row's conditional picks a column, and the point is
/// uniform in the cell. [`Distribution2D::pdf`] is exactly the density [`Distribution2D::sample`]
/// draws from (both use the same stored cumulative sums).
#[derive(Clone, Debug)]
pub struct Distribution2D {
    nx: usize,
    ny: usize,
    /// Over rows, by row sums.
    marginal: Discrete1D,
    /// Per row, over its columns (`None` for rows of zero weight, which are never picked).
    conditional: Vec<Option<Discrete1D>>,
}

impl Distribution2D {
    /// Bytes of its tables.
    pub fn memory_bytes(&self) -> usize {
        self.marginal.memory_bytes()
            + self
                .conditional
                .iter()
                .map(|c| c.as_ref().map_or(0, Discrete1D::memory_bytes))
                .sum::<usize>()
    }

    /// Builds from row-major weights (`weights[j * nx + i]` for column `i`, row `j`); `None` when
    /// the sizes do not match, a weight is negative or not finite, or all weights are zero.
    pub fn new(weights: &[f32], nx: usize, ny: usize) -> Option<Self> {
        if nx == 0 || ny == 0 || nx.checked_mul(ny)? != weights.len() {
            return None;
        }
        let mut conditional = Vec::with_capacity(ny);
        let mut row_sums = Vec::with_capacity(ny);
        for row in weights.chunks_exact(nx) {
            if row.iter().any(|w| !(*w >= 0.0) || !w.is_finite()) {
                return None;
            }
            let d = Discrete1D::new(row.iter().copied());
            row_sums.push(d.as_ref().map_or(0.0, |d| d.total() as f32));
            conditional.push(d);
        }
        let marginal = Discrete1D::new(row_sums)?;
        Some(Distribution2D {
            nx,
            ny,
            marginal,
            conditional,
        })
    }

    /// Number of columns.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Number of rows.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Probability of cell (`i`, `j`) (column, row); 0 outside the grid.
    pub(crate) fn cell_pmf(&self, i: usize, j: usize) -> f32 {
        if i >= self.nx || j >= self.ny {
            return 0.0;
        }
        match &self.conditional[j] {
            Some(c) => self.marginal.pmf(j) * c.pmf(i),
            None => 0.0,
        }
    }

    /// A point of `[0,1)^2` for `u` uniform in `[0,1)^2`, with its density (w.r.t. area on the
    /// unit square). `None` only in degenerate cases (a cell of zero probability reached by
    /// rounding).
    pub fn sample(&self, u: Vec2) -> Option<(Vec2, f32)> {
        let (i, j, r, pmf) = self.sample_cell(u)?;
        let p = Vec2::new(within_cell(i, r.x, self.nx), within_cell(j, r.y, self.ny));
        Some((p, pmf * (self.nx * self.ny) as f32))
    }

    /// Picks a cell for `u` uniform in `[0,1)^2`: its column and row, `u` rescaled to `[0,1)^2`
    /// within the choice (uniform and independent of it, for placing a point in the cell by
    /// another density), and the cell's probability (positive).
    pub(crate) fn sample_cell(&self, u: Vec2) -> Option<(usize, usize, Vec2, f32)> {
        let (j, uy) = self.marginal.sample_reuse(u.y);
        let cond = self.conditional[j].as_ref()?;
        let (i, ux) = cond.sample_reuse(u.x);
        let pmf = self.marginal.pmf(j) * cond.pmf(i);
        (pmf > 0.0).then_some((i, j, Vec2::new(ux, uy), pmf))
    }

    /// Density of [`Distribution2D::sample`] at `p` (0 outside `[0,1)^2`).
    pub fn pdf(&self, p: Vec2) -> f32 {
        if !(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0) {
            return 0.0;
        }
        let i = ((p.x * self.nx as f32) as usize).min(self.nx - 1);
        let j = ((p.y * self.ny as f32) as usize).min(self.ny - 1);
        self.cell_pmf(i, j) * (self.nx * self.ny) as f32
    }
}

/// `(i + t) / n` for `t` in `[0, 1)`, kept inside cell `i` of `n` as [`Distribution2D::pdf`]
/// bins it (rounding could otherwise carry a point into the next cell, which may have
/// probability 0).
#[inline]
fn within_cell(i: usize, t: f32, n: usize) -> f32 {
    let nf = n as f32;
    let mut x = (i as f32 + t) / nf;
    for _ in 0..4 {
        if ((x * nf) as usize) <= i && x < 1.0 {
            break;
        }
        x = next_down(x);
    }
    x
}

//! Tiles: the rectangles of pixels a render hands to its worker threads, and the probe each
//! worker owns while rendering them.
use tessera_core::integrator::{Counters, NoProbe, Probe};

/// A rectangle of pixels `[x0, x1) x [y0, y1)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    /// Left column.
    pub x0: u32,
    /// Top row.
    pub y0: u32,
    /// One past the right column.
    pub x1: u32,
    /// One past the bottom row.
    pub y1: u32,
}

/// The tiles covering a `width x height` image, in scanline order.
pub fn tiles(width: u32, height: u32, size: u32) -> Vec<Tile> {
    let size = size.max(1);
    let mut out = Vec::new();
    for y0 in (0..height).step_by(size as usize) {
        for x0 in (0..width).step_by(size as usize) {
            out.push(Tile {
                x0,
                y0,
                x1: (x0 + size).min(width),
                y1: (y0 + size).min(height),
            });
        }
    }
    out
}

/// A probe each worker thread owns while rendering tiles (see `render::render_span`); the
/// workers' probes are combined at the end.
pub trait TileProbe: Probe + Default + Send {
    /// Adds what another worker observed.
    fn absorb(&mut self, other: Self);
}

impl TileProbe for NoProbe {
    fn absorb(&mut self, _: Self) {}
}

impl TileProbe for Counters {
    fn absorb(&mut self, other: Self) {
        self.merge(&other);
    }
}

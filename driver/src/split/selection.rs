//! Which pixels a render computes: the whole image, a crop window, or one of N interleaved tile
//! sets (for splitting a render across processes or machines).
//!
//! The selection only chooses pixels; it never changes their values, because every sample's
//! random stream is a pure function of (seed, pixel, sample index). A part rendered with any
//! selection therefore holds exactly the bits the whole render holds for those pixels.
use crate::tile::{tiles, Tile};
use std::fmt;

/// A set of pixels of a `width x height` image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelSelection {
    /// Every pixel.
    #[default]
    All,
    /// The pixels of one rectangle `[x0, x1) x [y0, y1)`.
    Crop(Tile),
    /// Tile set `k` of `n` (1-based, like Slurm array indices): the tiles `i` of the image's
    /// scanline tile list (for the render's tile size) with `i % n == k - 1`.
    Tiles {
        /// Which set, `1..=n`.
        k: u32,
        /// How many sets.
        n: u32,
    },
}

impl PixelSelection {
    /// Checks that the selection makes sense for the image: a crop lies inside it and is not
    /// empty; a tile set exists (`1 <= k <= n`) and holds at least one tile.
    pub fn check(&self, width: u32, height: u32, tile_size: u32) -> Result<(), String> {
        match *self {
            PixelSelection::All => Ok(()),
            PixelSelection::Crop(t) => {
                if t.x0 >= t.x1 || t.y0 >= t.y1 {
                    Err(format!("{self} is an empty window"))
                } else if t.x1 > width || t.y1 > height {
                    Err(format!("{self} does not fit in the {width}x{height} image"))
                } else {
                    Ok(())
                }
            }
            PixelSelection::Tiles { k, n } => {
                if n == 0 || k == 0 || k > n {
                    return Err(format!("tile set {k}/{n}: need 1 <= K <= N"));
                }
                let total = tiles(width, height, tile_size).len();
                if (k - 1) as usize >= total {
                    return Err(format!(
                        "tile set {k}/{n} is empty: the {width}x{height} image has only {total} \
                         tiles of {tile_size} px (use fewer sets or a smaller --tile-size)"
                    ));
                }
                Ok(())
            }
        }
    }

    /// The rectangles to render, each inside one tile of the image's tile grid (so a crop is
    /// cut along tile edges into several rectangles), in scanline order of the grid.
    pub(crate) fn rects(&self, width: u32, height: u32, tile_size: u32) -> Vec<Tile> {
        let all = tiles(width, height, tile_size);
        match *self {
            PixelSelection::All => all,
            PixelSelection::Crop(c) => all
                .into_iter()
                .filter_map(|t| {
                    let r = Tile {
                        x0: t.x0.max(c.x0),
                        y0: t.y0.max(c.y0),
                        x1: t.x1.min(c.x1),
                        y1: t.y1.min(c.y1),
                    };
                    (r.x0 < r.x1 && r.y0 < r.y1).then_some(r)
                })
                .collect(),
            PixelSelection::Tiles { k, n } => all
                .into_iter()
                .enumerate()
                .filter(|(i, _)| n > 0 && k > 0 && *i as u64 % n as u64 == (k - 1) as u64)
                .map(|(_, t)| t)
                .collect(),
        }
    }

    /// The smallest rectangle holding every selected pixel (`None` if none is selected).
    pub fn bounds(&self, width: u32, height: u32, tile_size: u32) -> Option<Tile> {
        self.rects(width, height, tile_size)
            .into_iter()
            .reduce(|a, b| Tile {
                x0: a.x0.min(b.x0),
                y0: a.y0.min(b.y0),
                x1: a.x1.max(b.x1),
                y1: a.y1.max(b.y1),
            })
    }

    /// Parses the text [`fmt::Display`] writes: `all`, `crop X0,Y0,X1,Y1` or `tiles K/N`.
    pub fn parse(s: &str) -> Result<PixelSelection, String> {
        let s = s.trim();
        if s == "all" {
            Ok(PixelSelection::All)
        } else if let Some(c) = s.strip_prefix("crop ") {
            parse_crop(c).map(PixelSelection::Crop)
        } else if let Some(t) = s.strip_prefix("tiles ") {
            let (k, n) = parse_tile_set(t)?;
            Ok(PixelSelection::Tiles { k, n })
        } else {
            Err(format!("unknown pixel selection \"{s}\""))
        }
    }
}

impl fmt::Display for PixelSelection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PixelSelection::All => write!(f, "all"),
            PixelSelection::Crop(t) => write!(f, "crop {},{},{},{}", t.x0, t.y0, t.x1, t.y1),
            PixelSelection::Tiles { k, n } => write!(f, "tiles {k}/{n}"),
        }
    }
}

/// Parses `x0,y0,x1,y1` (the window `[x0, x1) x [y0, y1)`).
pub fn parse_crop(s: &str) -> Result<Tile, String> {
    let v: Vec<&str> = s.split(',').map(str::trim).collect();
    let bad = || format!("expected x0,y0,x1,y1 (pixels, x1 > x0, y1 > y0), found \"{s}\"");
    if v.len() != 4 {
        return Err(bad());
    }
    let mut n = [0u32; 4];
    for (d, t) in n.iter_mut().zip(&v) {
        *d = t.parse().map_err(|_| bad())?;
    }
    if n[2] <= n[0] || n[3] <= n[1] {
        return Err(bad());
    }
    Ok(Tile {
        x0: n[0],
        y0: n[1],
        x1: n[2],
        y1: n[3],
    })
}

/// Parses `K/N` with `1 <= K <= N`.
pub fn parse_tile_set(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected K/N with 1 <= K <= N, found \"{s}\"");
    let (k, n) = s.trim().split_once('/').ok_or_else(bad)?;
    let k: u32 = k.trim().parse().map_err(|_| bad())?;
    let n: u32 = n.trim().parse().map_err(|_| bad())?;
    if k == 0 || k > n {
        return Err(bad());
    }
    Ok((k, n))
}

/// Parses a sample range `a..b` (`a < b`).
pub fn parse_sample_range(s: &str) -> Result<std::ops::Range<u64>, String> {
    let bad = || format!("expected a..b with a < b (sample indices), found \"{s}\"");
    let (a, b) = s.trim().split_once("..").ok_or_else(bad)?;
    let a: u64 = a.trim().parse().map_err(|_| bad())?;
    let b: u64 = b.trim().parse().map_err(|_| bad())?;
    if a >= b {
        return Err(bad());
    }
    Ok(a..b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn covered(sel: PixelSelection, w: u32, h: u32, ts: u32) -> Vec<u32> {
        let mut c = vec![0u32; (w * h) as usize];
        for r in sel.rects(w, h, ts) {
            for y in r.y0..r.y1 {
                for x in r.x0..r.x1 {
                    c[(y * w + x) as usize] += 1;
                }
            }
        }
        c
    }

    #[test]
    fn tile_sets_partition_the_image() {
        let (w, h, ts) = (37, 23, 8);
        let mut total = vec![0u32; (w * h) as usize];
        for k in 1..=3 {
            let c = covered(PixelSelection::Tiles { k, n: 3 }, w, h, ts);
            for (t, c) in total.iter_mut().zip(c) {
                *t += c;
            }
        }
        assert!(total.iter().all(|&c| c == 1));
    }

    #[test]
    fn crop_covers_exactly_its_window() {
        let crop = Tile {
            x0: 5,
            y0: 3,
            x1: 30,
            y1: 17,
        };
        let c = covered(PixelSelection::Crop(crop), 37, 23, 8);
        for y in 0..23 {
            for x in 0..37 {
                let inside = (5..30).contains(&x) && (3..17).contains(&y);
                assert_eq!(c[(y * 37 + x) as usize], inside as u32, "({x}, {y})");
            }
        }
        assert_eq!(PixelSelection::Crop(crop).bounds(37, 23, 8), Some(crop));
    }

    #[test]
    fn parse_and_display_round_trip() {
        for s in ["all", "crop 1,2,3,4", "tiles 2/8"] {
            assert_eq!(PixelSelection::parse(s).unwrap().to_string(), s);
        }
        assert!(parse_crop("1,2,1,4").is_err());
        assert!(parse_crop("1,2,3").is_err());
        assert!(parse_tile_set("0/4").is_err());
        assert!(parse_tile_set("5/4").is_err());
        assert_eq!(parse_sample_range("4..8"), Ok(4..8));
        assert!(parse_sample_range("8..8").is_err());
        assert!(PixelSelection::Tiles { k: 5, n: 8 }.check(8, 8, 4).is_err());
        assert!(PixelSelection::Crop(parse_crop("0,0,9,8").unwrap())
            .check(8, 8, 4)
            .is_err());
    }
}

//! A worker's copy of one tile's sums: what the tile loop adds samples to, loaded from the
//! framebuffer when the tile starts and written back when it ends, so that the framebuffer
//! itself is only touched under its lock, by copies.
use crate::framebuffer::Framebuffer;
use crate::tile::Tile;
use tessera_core::film::PixelAccum;
use tessera_core::glam::Vec2;
use tessera_core::integrator::{xyz_squared, AovIntegrator};
use tessera_core::render::CameraSample;
use tessera_core::scene::Scene;
use tessera_core::splat::{Footprint, SplatWeights};
use tessera_core::Color;

/// What a worker adds a tile's samples to: a copy of the tile's accumulators, of their splatted
/// sums when the scene splats, and of the XYZ squares' and surface variables' sums when the
/// framebuffer gathers them ([`Framebuffer::squares`], [`Framebuffer::aovs`]). A worker keeps one and reloads it for each tile, so its buffers
/// are allocated once.
#[derive(Debug)]
pub(crate) struct TileSums<'a> {
    /// The tile's pixels' accumulators, row-major within the tile.
    pub(crate) pixels: Vec<PixelAccum>,
    /// Their splatted sums (empty when the scene does not splat).
    sums: Vec<f32>,
    footprint: Option<&'a Footprint>,
    /// The same for the samples' XYZ squares, when gathered.
    squares: Option<Box<TileSums<'a>>>,
    /// The same for each gathered surface variable ([`Framebuffer::aovs`]).
    aovs: Vec<TileSums<'a>>,
}

impl<'a> TileSums<'a> {
    /// Empty sums, to which samples splat over `footprint`.
    pub(crate) fn new(footprint: Option<&'a Footprint>) -> Self {
        TileSums {
            pixels: Vec::new(),
            sums: Vec::new(),
            footprint,
            squares: None,
            aovs: Vec::new(),
        }
    }

    /// Replaces the contents with the sums of tile `t` of `fb` (whose splats' reach must be
    /// that of the footprint).
    pub(crate) fn load(&mut self, t: &Tile, fb: &Framebuffer) {
        self.pixels.clear();
        self.sums.clear();
        let width = fb.width as usize;
        for y in t.y0..t.y1 {
            let row = y as usize * width;
            let (a, b) = (row + t.x0 as usize, row + t.x1 as usize);
            self.pixels.extend_from_slice(&fb.pixels[a..b]);
            if let Some(s) = &fb.splats {
                self.sums
                    .extend_from_slice(&s.sums[a * s.stride()..b * s.stride()]);
            }
        }
        match &fb.squares {
            Some(q) => self
                .squares
                .get_or_insert_with(|| Box::new(TileSums::new(self.footprint)))
                .load(t, q),
            None => self.squares = None,
        }
        let footprint = self.footprint;
        self.aovs
            .resize_with(fb.aovs.len(), || TileSums::new(footprint));
        for (sums, g) in self.aovs.iter_mut().zip(&fb.aovs) {
            sums.load(t, &g.fb);
        }
    }

    /// Adds a sample of value `c`, `offset` from its pixel's centre, to the tile's pixel `k`
    /// (and its XYZ square to the squares, when gathered); a non-finite value is counted as
    /// dropped and splats nothing.
    #[inline]
    pub(crate) fn add(&mut self, k: usize, c: Color, offset: Vec2) {
        let w = self.footprint.map(|f| f.weights(offset));
        self.add_weighted(k, c, w.as_ref());
    }

    /// [`TileSums::add`] with the sample's splat weights found (`None` when nothing splats):
    /// the colour and its square splat with the same weights.
    #[inline]
    fn add_weighted(&mut self, k: usize, c: Color, w: Option<&SplatWeights>) {
        self.pixels[k].add(c);
        if let (Some(f), Some(w)) = (self.footprint, w) {
            if c.is_finite() {
                let s = f.stride();
                f.add_weighted(&mut self.sums[k * s..(k + 1) * s], w, c);
            }
        }
        if let Some(q) = &mut self.squares {
            q.add_weighted(k, xyz_squared(c), w);
        }
    }

    /// Writes the tile's sums back into place in `fb`.
    pub(crate) fn write(&self, t: &Tile, fb: &mut Framebuffer) {
        let tw = (t.x1 - t.x0) as usize;
        let width = fb.width as usize;
        let stride = self.footprint.map_or(0, Footprint::stride);
        for (row, y) in (t.y0..t.y1).enumerate() {
            let dst = y as usize * width + t.x0 as usize;
            fb.pixels[dst..dst + tw].copy_from_slice(&self.pixels[row * tw..(row + 1) * tw]);
            if let Some(s) = &mut fb.splats {
                let src = &self.sums[row * tw * stride..(row + 1) * tw * stride];
                s.sums[dst * stride..(dst + tw) * stride].copy_from_slice(src);
            }
        }
        if let (Some(q), Some(to)) = (&self.squares, &mut fb.squares) {
            q.write(t, to);
        }
        for (sums, g) in self.aovs.iter().zip(&mut fb.aovs) {
            sums.write(t, &mut g.fb);
        }
    }

    /// Adds the variables `aovs` (those of the framebuffer this was loaded from, in order) of
    /// the sample whose camera ray is `cam`, `offset` from the centre of the tile's pixel `k`:
    /// one cast for all of them (none when there are none), each value weighted as the colour's
    /// was.
    #[inline]
    pub(crate) fn add_aovs(
        &mut self,
        k: usize,
        offset: Vec2,
        scene: &Scene,
        cam: &CameraSample,
        aovs: &[AovIntegrator],
    ) {
        if aovs.is_empty() {
            return;
        }
        let hit = scene.intersect(&cam.ray);
        let w = self.footprint.map(|f| f.weights(offset));
        for (sums, a) in self.aovs.iter_mut().zip(aovs) {
            let v = a.value(scene, &cam.ray, hit.as_ref());
            sums.add_weighted(k, cam.weigh(v), w.as_ref());
        }
    }
}

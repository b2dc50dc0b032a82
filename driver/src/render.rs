//! Renders a whole image: a fixed list of tiles handed to worker threads by an atomic cursor.
//!
//! Each pixel belongs to exactly one tile and each tile to exactly one worker, which adds the
//! pixel's samples in sample-index order; composition only copies tiles into place. The result
//! is therefore the same bits for any thread count and any tile size.
//!
//! `RenderOptions::pixels` restricts the render to a crop window or a tile set (see
//! [`PixelSelection`]); the selected pixels get exactly the bits the whole render gives them and
//! the others stay empty.
use crate::render_groups::{render_tile_groups, Sharing};
pub use crate::split::selection::PixelSelection;
pub use crate::tile::{tiles, Tile, TileProbe};
use crossbeam_channel::unbounded;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use tessera_core::film::PixelAccum;
use tessera_core::integrator::Integrator;
use tessera_core::integrator::NoProbe;
use tessera_core::render::{render_samples_cached, reuses, GroupCache, PixelCache};
use tessera_core::scene::Scene;

/// How to render.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// Samples per pixel (the sample indices rendered are `samples`).
    pub samples: Range<u64>,
    /// Worker threads (at least 1).
    pub threads: usize,
    /// Tile edge in pixels (never derived from the thread count).
    pub tile_size: u32,
    /// Scene seed.
    pub seed: u64,
    /// Which pixels to render (the rest of the framebuffer stays empty).
    pub pixels: PixelSelection,
}

impl Default for RenderOptions {
    /// One sample per pixel (index 0), one thread, 32-pixel tiles, seed 0, the whole image.
    fn default() -> Self {
        RenderOptions {
            samples: 0..1,
            threads: 1,
            tile_size: 32,
            seed: 0,
            pixels: PixelSelection::default(),
        }
    }
}

/// Accumulated samples of every pixel, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Sums per pixel.
    pub pixels: Vec<PixelAccum>,
}

impl Framebuffer {
    /// An empty buffer.
    pub fn new(width: u32, height: u32) -> Self {
        Framebuffer {
            width,
            height,
            pixels: vec![PixelAccum::default(); width as usize * height as usize],
        }
    }
    /// Mean of each pixel.
    pub fn rgb(&self) -> Vec<[f32; 3]> {
        self.pixels.iter().map(|p| p.mean()).collect()
    }
    /// Samples dropped because they were not finite.
    pub fn dropped(&self) -> u64 {
        self.pixels.iter().map(|p| p.dropped).sum()
    }
    /// Accumulator of pixel `(x, y)`.
    pub fn at(&self, x: u32, y: u32) -> &PixelAccum {
        &self.pixels[y as usize * self.width as usize + x as usize]
    }
}

/// Renders the selected pixels (`opts.pixels`); `progress(tiles_done, tiles_total)` is called on
/// the calling thread as tiles arrive.
pub fn render(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Framebuffer {
    let mut fb = Framebuffer::new(scene.camera.width, scene.camera.height);
    render_tiles::<NoProbe>(scene, integrator, opts, &mut fb, None, None, progress);
    fb
}

/// [`render`] with a probe per worker thread observing every sample (e.g. [`Counters`](tessera_core::integrator::Counters) for
/// `--stats`), combined at the end. A probe only observes: the image is the same bits, and sums
/// of counts do not depend on the thread count or the tile size.
pub fn render_probed<P: TileProbe>(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> (Framebuffer, P) {
    let mut fb = Framebuffer::new(scene.camera.width, scene.camera.height);
    let probe = render_tiles(scene, integrator, opts, &mut fb, None, None, progress);
    (fb, probe)
}

/// Panics unless `fb` is the scene's size (a caller's mistake: start from `Framebuffer::new`).
fn check_size(scene: &Scene, fb: &Framebuffer, what: &str) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    assert!(
        (fb.width, fb.height) == (w, h) && fb.pixels.len() == w as usize * h as usize,
        "{what}: the framebuffer is {}x{}, the scene {w}x{h}",
        fb.width,
        fb.height
    );
}

/// Adds the samples `opts.samples` of every selected pixel to the sums already in `fb`, as if
/// the render had gone on: rendering `0..a` and then `a..b` into the same buffer gives the same
/// bits as rendering `0..b` at once (each pixel continues its own sum, in sample-index order).
///
/// # Panics
/// If `fb` is not the scene's size (a caller's mistake: start from `Framebuffer::new`).
pub fn render_into(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    progress: &mut dyn FnMut(usize, usize),
) {
    check_size(scene, fb, "render_into");
    render_tiles::<NoProbe>(scene, integrator, opts, fb, None, None, progress);
}

/// Brings every selected pixel of `fb` to `targets[i]` samples (`targets` row-major, one per
/// pixel of the image), each pixel continuing from its own count (`count + dropped`);
/// `opts.samples` is not used. Used by adaptive sampling, where pixels hold different counts:
/// a pixel's bits equal a plain render of its first `targets[i]` samples. (With path reuse, a
/// sample's value also depends on which pixels of its group take it in this call, those whose
/// range holds its index; tile edges are then rounded up so that tiles hold whole groups, see
/// `render_groups.rs`.) With `stop`, no tile
/// is started once it is set (the tiles not rendered keep their sums); returns whether every
/// tile was rendered.
///
/// # Panics
/// If `fb` is not the scene's size or `targets` has another length.
pub fn render_into_targets(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    targets: &[u64],
    stop: Option<&AtomicBool>,
    progress: &mut dyn FnMut(usize, usize),
) -> bool {
    check_size(scene, fb, "render_into_targets");
    assert_eq!(
        targets.len(),
        fb.pixels.len(),
        "render_into_targets: one target per pixel"
    );
    let (w, h) = (scene.camera.width, scene.camera.height);
    // The tile count is the loop's own (it may round the tile edge), told with each tile.
    let mut complete = opts.pixels.rects(w, h, opts.tile_size).is_empty();
    render_tiles::<NoProbe>(
        scene,
        integrator,
        opts,
        fb,
        stop,
        Some(targets),
        &mut |d, t| {
            complete = d == t;
            progress(d, t)
        },
    );
    complete
}

/// Brings every selected pixel of `fb` to `opts.samples.end` samples, each pixel continuing from
/// its own count (`count + dropped`, so pixels may start at different sample indices;
/// `opts.samples.start` is not used). Workers check `stop` before each tile and take no new tile
/// once it is set; the tiles not rendered keep their sums. Returns whether every tile was
/// rendered. The bits equal a single render of `0..opts.samples.end`, however the work was split
/// or interrupted.
///
/// # Panics
/// If `fb` is not the scene's size.
pub fn render_into_until(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    stop: &AtomicBool,
    progress: &mut dyn FnMut(usize, usize),
) -> bool {
    check_size(scene, fb, "render_into_until");
    let (w, h) = (scene.camera.width, scene.camera.height);
    let total = opts.pixels.rects(w, h, opts.tile_size).len();
    let mut done = 0;
    render_tiles::<NoProbe>(
        scene,
        integrator,
        opts,
        fb,
        Some(stop),
        None,
        &mut |d, t| {
            done = d;
            progress(d, t)
        },
    );
    done == total
}

/// The tile loop, in place: each tile's accumulators start from the sums in `fb` and take the
/// samples `opts.samples` in order. With `stop` (resumable mode), each pixel instead continues
/// from its own count up to `opts.samples.end`, and no tile is started once `stop` is set (the
/// tiles not rendered keep their sums). With `targets`, each pixel continues from its own count
/// up to its own target instead. Pixels outside the selection keep their sums.
fn render_tiles<P: TileProbe>(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    stop: Option<&AtomicBool>,
    targets: Option<&[u64]>,
    progress: &mut dyn FnMut(usize, usize),
) -> P {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let reuse = reuses(integrator);
    let (sharing, tile_size) = Sharing::choose(reuse, targets.is_some(), opts.tile_size);
    let mut list = opts.pixels.rects(w, h, tile_size);
    if let Some(targets) = targets {
        largest_first(&mut list, targets, &fb.pixels, w);
    }
    let mut total = P::default();
    // The finished tiles, written into `fb` once the workers (which read its sums) are done:
    // `fb` is updated in place, with no copy of the whole buffer per call.
    let mut finished = Vec::with_capacity(list.len());
    let start = &fb.pixels;
    let cursor = AtomicUsize::new(0);
    let (tx, rx) = unbounded::<(usize, Vec<PixelAccum>)>();
    let threads = opts.threads.max(1).min(list.len().max(1));
    std::thread::scope(|s| {
        let mut workers = Vec::with_capacity(threads);
        for _ in 0..threads {
            let tx = tx.clone();
            let (list, cursor) = (&list, &cursor);
            workers.push(s.spawn(move || {
                let mut probe = P::default();
                let mut cache = PixelCache::default();
                let mut groups = GroupCache::default();
                loop {
                    if stop.is_some_and(|f| f.load(Ordering::Relaxed)) {
                        break;
                    }
                    let i = cursor.fetch_add(1, Ordering::Relaxed);
                    let Some(t) = list.get(i) else { break };
                    let mut acc = Vec::with_capacity(((t.x1 - t.x0) * (t.y1 - t.y0)) as usize);
                    for y in t.y0..t.y1 {
                        let row = y as usize * w as usize;
                        acc.extend_from_slice(&start[row + t.x0 as usize..row + t.x1 as usize]);
                    }
                    let range = |a: &PixelAccum, x: u32, y: u32| {
                        let own = a.count + a.dropped;
                        match (targets, stop) {
                            (Some(t), _) => own..t[y as usize * w as usize + x as usize],
                            (None, Some(_)) => own..opts.samples.end,
                            (None, None) => opts.samples.clone(),
                        }
                    };
                    if reuse {
                        render_tile_groups(
                            scene,
                            integrator,
                            opts.seed,
                            t,
                            &mut acc,
                            &range,
                            sharing,
                            &mut groups,
                            &mut probe,
                        );
                        if tx.send((i, acc)).is_err() {
                            break;
                        }
                        continue;
                    }
                    let mut k = 0;
                    for y in t.y0..t.y1 {
                        for x in t.x0..t.x1 {
                            let a = &mut acc[k];
                            let samples = range(a, x, y);
                            render_samples_cached(
                                scene,
                                integrator,
                                opts.seed,
                                x,
                                y,
                                samples,
                                &mut cache,
                                &mut probe,
                                |c| a.add(c),
                            );
                            k += 1;
                        }
                    }
                    if tx.send((i, acc)).is_err() {
                        break;
                    }
                }
                probe
            }));
        }
        drop(tx);
        let mut done = 0;
        for tile in rx.iter() {
            finished.push(tile);
            done += 1;
            progress(done, list.len());
        }
        for worker in workers {
            match worker.join() {
                Ok(p) => total.absorb(p),
                Err(e) => std::panic::resume_unwind(e),
            }
        }
    });
    for (i, acc) in finished {
        let t = list[i];
        let tw = (t.x1 - t.x0) as usize;
        for (row, y) in (t.y0..t.y1).enumerate() {
            let dst = y as usize * w as usize + t.x0 as usize;
            fb.pixels[dst..dst + tw].copy_from_slice(&acc[row * tw..(row + 1) * tw]);
        }
    }
    total
}

/// Orders `tiles` by the samples they still take to reach `targets` (row-major, `width` wide),
/// most first, ties in the given order. With per-pixel targets (adaptive passes) a few tiles can
/// hold much of a pass's work; started last, one of them would keep one thread busy while the
/// others wait. Tile order changes no bit: each pixel's sum is its own, in sample order.
fn largest_first(tiles: &mut [Tile], targets: &[u64], pixels: &[PixelAccum], width: u32) {
    let work = |t: &Tile| -> u64 {
        let mut sum = 0u64;
        for y in t.y0..t.y1 {
            for x in t.x0..t.x1 {
                let i = y as usize * width as usize + x as usize;
                let p = &pixels[i];
                sum += targets[i].saturating_sub(p.count + p.dropped);
            }
        }
        sum
    };
    tiles.sort_by_cached_key(|t| core::cmp::Reverse(work(t)));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tiles go most work first (what each pixel still lacks of its target, not the target
    /// itself), ties in scanline order.
    #[test]
    fn largest_first_orders_by_remaining_work() {
        let (w, h) = (8u32, 4u32);
        let mut list = tiles(w, h, 2);
        assert_eq!(list.len(), 8);
        let mut pixels = vec![PixelAccum::default(); (w * h) as usize];
        let mut targets = vec![1u64; (w * h) as usize];
        // Tile 6 (x 4..6, y 2..4): 5 more in one pixel. Tile 2 (x 4..6, y 0..2): 3 more,
        // spread. Tile 5 (x 2..4, y 2..4): a high target it has already reached.
        targets[2 * 8 + 5] = 6;
        targets[4] = 2;
        targets[5] = 2;
        targets[8 + 4] = 2;
        targets[3 * 8 + 3] = 9;
        pixels[3 * 8 + 3].count = 9;
        largest_first(&mut list, &targets, &pixels, w);
        let order: Vec<(u32, u32)> = list.iter().map(|t| (t.x0, t.y0)).collect();
        assert_eq!(
            order,
            [
                (4, 2),
                (4, 0),
                (0, 0),
                (2, 0),
                (6, 0),
                (0, 2),
                (6, 2),
                (2, 2)
            ]
        );
    }
}

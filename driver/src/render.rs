//! The tile loop: a fixed list of tiles handed to worker threads by an atomic cursor, each
//! pixel taking the samples of a [`Span`] from the core's [`RenderJob`].
//!
//! Each pixel belongs to exactly one tile and each tile to exactly one worker, which adds the
//! pixel's samples in sample-index order; composition only copies tiles into place. The result
//! is therefore the same bits for any thread count and any tile size.
//!
//! [`RenderOptions::pixels`] restricts the render to a crop window or a tile set (see
//! [`PixelSelection`]); the selected pixels get exactly the bits the whole render gives them and
//! the others stay empty.
pub use crate::framebuffer::{Framebuffer, GatheredAov};
use crate::render_groups::{render_tile_groups, Sharing};
pub use crate::splats::Splats;
pub use crate::split::selection::PixelSelection;
pub use crate::tile::{tiles, Tile, TileProbe};
use crate::tile_sums::TileSums;
use crossbeam_channel::unbounded;
use std::cell::Cell;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};
use tessera_core::film::PixelAccum;
use tessera_core::integrator::{AovIntegrator, NoProbe, Probe, RayTally};
use tessera_core::render::{GroupCache, PixelCache, RenderJob};
use tessera_core::splat::Footprint;

/// How to split a render over threads and which pixels to render: nothing here changes a bit
/// of the selected pixels.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// Worker threads (at least 1).
    pub threads: usize,
    /// Tile edge in pixels (never derived from the thread count).
    pub tile_size: u32,
    /// Which pixels to render (the rest of the framebuffer stays empty).
    pub pixels: PixelSelection,
}

impl Default for RenderOptions {
    /// One thread, 32-pixel tiles, the whole image.
    fn default() -> Self {
        RenderOptions {
            threads: 1,
            tile_size: 32,
            pixels: PixelSelection::default(),
        }
    }
}

/// Which samples each selected pixel takes in one call of [`render_span`].
#[derive(Clone, Debug)]
pub enum Span<'a> {
    /// Sample indices `a..b` for every pixel, added to the sums already there: rendering `0..a`
    /// and then `a..b` into the same buffer gives the same bits as `0..b` at once.
    Fixed(Range<u64>),
    /// Each pixel continues from its own count (`count + dropped`) up to this many samples, so
    /// pixels may start at different indices (a pass of a progressive render, or one resumed).
    UpTo(u64),
    /// Each pixel continues from its own count up to its own target (row-major, one per pixel
    /// of the image): adaptive passes. With path reuse, a sample's value also depends on which
    /// pixels of its group take it in this call; tile edges are then rounded up so that tiles
    /// hold whole groups (see `render_groups.rs`). The only span whose pixels count the rays
    /// their samples cast ([`PixelAccum::rays`], what adaptive sampling prices samples by).
    Targets(&'a [u64]),
}

impl Span<'_> {
    /// The samples pixel `(x, y)`, holding `a`, takes (`width` is the image's).
    fn of(&self, a: &PixelAccum, x: u32, y: u32, width: u32) -> Range<u64> {
        let own = a.count + a.dropped;
        match self {
            Span::Fixed(r) => r.clone(),
            Span::UpTo(end) => own..*end,
            Span::Targets(t) => own..t[y as usize * width as usize + x as usize],
        }
    }
}

/// What a call of [`render_span`] did.
#[derive(Clone, Debug)]
pub struct Rendered<P> {
    /// Whether every tile was rendered (false only when the stop flag cut the call short).
    pub complete: bool,
    /// The workers' probes, combined.
    pub probe: P,
}

/// Renders samples `samples` of the selected pixels into a new framebuffer; `progress(tiles_done,
/// tiles_total)` is called on the calling thread as tiles arrive.
pub fn render(
    job: &RenderJob,
    samples: Range<u64>,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Framebuffer {
    let mut fb = Framebuffer::for_job(job);
    render_span::<NoProbe>(job, opts, &mut fb, Span::Fixed(samples), None, progress);
    fb
}

/// The tile loop: every selected pixel of `fb` takes the samples `span` gives it, added to its
/// sums in sample-index order; pixels outside the selection keep their sums. With `stop`, no tile
/// is started once it is set (the tiles not rendered keep their sums, and the result says the
/// call was not complete). A probe per worker thread (e.g.
/// [`Counters`](tessera_core::integrator::Counters) for `--stats`) observes every sample; they
/// are combined at the end. A probe only observes: the image is the same bits, and sums of
/// counts do not depend on the thread count or the tile size.
///
/// The bits of each pixel depend only on the job, the pixel and the samples it took, never on
/// the thread count, the tile size, the tile order or how the work was split into calls.
///
/// # Panics
/// If `fb` is not the job's image size, or `Span::Targets` has another length (a caller's
/// mistake: start from [`Framebuffer::for_job`]).
pub fn render_span<P: TileProbe>(
    job: &RenderJob,
    opts: &RenderOptions,
    fb: &mut Framebuffer,
    span: Span,
    stop: Option<&AtomicBool>,
    progress: &mut dyn FnMut(usize, usize),
) -> Rendered<P> {
    let (w, h) = job.size();
    assert!(
        (fb.width, fb.height) == (w, h) && fb.pixels.len() == w as usize * h as usize,
        "render_span: the framebuffer is {}x{}, the scene {w}x{h}",
        fb.width,
        fb.height
    );
    assert!(
        fb.splats.as_ref().map(|s| s.reach) == job.scene.splat.as_ref().map(Footprint::reach)
            && fb
                .splats
                .as_ref()
                .is_none_or(|s| s.sums.len() == fb.pixels.len() * s.stride()),
        "render_span: the framebuffer does not splat as the scene does"
    );
    let targets = match span {
        Span::Targets(t) => {
            assert_eq!(
                t.len(),
                fb.pixels.len(),
                "render_span: one target per pixel"
            );
            Some(t)
        }
        _ => None,
    };
    let reuse = job.reuses();
    let (sharing, tile_size) = Sharing::choose(reuse, targets.is_some(), opts.tile_size);
    // Adaptive passes price each pixel's samples by the rays they cast; other renders leave
    // the count as it is (counting costs about 0.7% of a render's instructions).
    let count_rays = targets.is_some();
    let mut list = opts.pixels.rects(w, h, tile_size);
    if let Some(targets) = targets {
        largest_first(&mut list, targets, &fb.pixels, w);
    }
    let mut total = P::default();
    // Each worker copies a tile's sums out of `fb` when it starts the tile and writes them back
    // when it ends it, under this lock (held only for the copies). Tiles are disjoint, so a tile
    // reads exactly the sums it would have read had the tiles been rendered one after another;
    // only a worker's own tile copy exists beside `fb`.
    assert!(
        fb.squares
            .as_ref()
            .is_none_or(|q| q.pixels.len() == fb.pixels.len()
                && q.splats.as_ref().map(|s| s.reach) == fb.splats.as_ref().map(|s| s.reach)),
        "render_span: the squares are not shaped as the framebuffer"
    );
    assert!(
        fb.aovs.is_empty() || !reuse,
        "render_span: an integrator that reuses paths cannot gather surface variables"
    );
    assert!(
        fb.aovs.iter().all(|g| g.fb.pixels.len() == fb.pixels.len()
            && g.fb.splats.as_ref().map(|s| s.reach) == fb.splats.as_ref().map(|s| s.reach)),
        "render_span: the surface variables are not shaped as the framebuffer"
    );
    let aovs: Vec<AovIntegrator> = fb.aovs.iter().map(|g| g.aov).collect();
    let shared = Mutex::new(&mut *fb);
    let cursor = AtomicUsize::new(0);
    let (tx, rx) = unbounded::<usize>();
    let threads = opts.threads.max(1).min(list.len().max(1));
    let mut done = 0;
    std::thread::scope(|s| {
        let mut workers = Vec::with_capacity(threads);
        for _ in 0..threads {
            let tx = tx.clone();
            let (list, cursor, span, shared, aovs) = (&list, &cursor, &span, &shared, &aovs);
            workers.push(s.spawn(move || {
                let mut probe = P::default();
                let mut work = TileWork::new(job);
                loop {
                    if stop.is_some_and(|f| f.load(Ordering::Relaxed)) {
                        break;
                    }
                    let i = cursor.fetch_add(1, Ordering::Relaxed);
                    let Some(t) = list.get(i) else { break };
                    work.acc.load(t, &lock(shared));
                    let range = |a: &PixelAccum, x: u32, y: u32| span.of(a, x, y, w);
                    if count_rays {
                        let rays = Cell::new(0);
                        let mut tally = RayTally::new(&mut probe, &rays);
                        work.tile(t, &range, sharing, aovs, &mut tally, Some(&rays));
                    } else {
                        work.tile(t, &range, sharing, aovs, &mut probe, None);
                    }
                    work.acc.write(t, &mut lock(shared));
                    if tx.send(i).is_err() {
                        break;
                    }
                }
                probe
            }));
        }
        drop(tx);
        for _ in rx.iter() {
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
    let complete = done == list.len();
    Rendered {
        complete,
        probe: total,
    }
}

/// What a worker thread keeps from tile to tile: the tile's sums and the samplers' caches.
struct TileWork<'a> {
    job: &'a RenderJob<'a>,
    acc: TileSums<'a>,
    cache: PixelCache,
    groups: GroupCache,
}

impl<'a> TileWork<'a> {
    fn new(job: &'a RenderJob<'a>) -> Self {
        TileWork {
            job,
            acc: TileSums::new(job.scene.splat.as_ref()),
            cache: PixelCache::default(),
            groups: GroupCache::default(),
        }
    }

    /// Renders tile `t` (its sums loaded in `acc`): each pixel takes the samples `range` gives
    /// it, observed by `probe`; with `rays` (the cell `probe` counts rays into), each pixel's
    /// ray count grows by the rays its samples cast.
    fn tile<Q: Probe>(
        &mut self,
        t: &Tile,
        range: &dyn Fn(&PixelAccum, u32, u32) -> Range<u64>,
        sharing: Sharing,
        aovs: &[AovIntegrator],
        probe: &mut Q,
        rays: Option<&Cell<u64>>,
    ) {
        let job = self.job;
        let acc = &mut self.acc;
        if job.reuses() {
            let groups = &mut self.groups;
            render_tile_groups(job, t, acc, range, sharing, groups, (probe, rays));
            return;
        }
        let mut k = 0;
        for y in t.y0..t.y1 {
            for x in t.x0..t.x1 {
                let samples = range(&acc.pixels[k], x, y);
                // A sample's rays are all cast before its value arrives (a batch's before the
                // batch's first value): each value takes those not yet counted.
                let add = |c, o, cam: &_| {
                    acc.add(k, c, o);
                    if let Some(rays) = rays {
                        acc.pixels[k].rays += rays.take();
                    }
                    acc.add_aovs(k, o, job.scene, cam, aovs);
                };
                job.pixel_alone(x, y, samples, &mut self.cache, probe, add);
                k += 1;
            }
        }
    }
}

/// The lock on the framebuffer's sums. A worker that panicked while holding it has its panic
/// re-raised when the workers are joined, so a poisoned lock's contents are never returned.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
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

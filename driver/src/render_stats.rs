//! `tessera render --stats`: the tile render of [`crate::render`], with a [`Counters`] probe per
//! worker thread, summed at the end.
//!
//! Each sample is `render_sample_probed`, which returns the same value as `render_sample` (a
//! probe only observes), added to its pixel in sample-index order as in the ordinary render: the
//! image is the same bits. The counts are sums over samples, so they do not depend on the thread
//! count or the tile size either.
use crate::render::{render, tiles, Framebuffer, RenderOptions};
use crossbeam_channel::unbounded;
use std::sync::atomic::{AtomicUsize, Ordering};
use tessera_core::film::PixelAccum;
use tessera_core::integrator::{Counters, Integrator};
use tessera_core::render::render_sample_probed;
use tessera_core::scene::Scene;

/// Renders every pixel like [`crate::render::render`] and counts the work done.
pub fn render_with_stats(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> (Framebuffer, Counters) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let list = tiles(w, h, opts.tile_size);
    let mut fb = Framebuffer::new(w, h);
    let mut total = Counters::default();
    let cursor = AtomicUsize::new(0);
    let (tx, rx) = unbounded::<(usize, Vec<PixelAccum>)>();
    let threads = opts.threads.max(1).min(list.len().max(1));
    std::thread::scope(|s| {
        let mut workers = Vec::with_capacity(threads);
        for _ in 0..threads {
            let tx = tx.clone();
            let (list, cursor) = (&list, &cursor);
            workers.push(s.spawn(move || {
                let mut counters = Counters::default();
                loop {
                    let i = cursor.fetch_add(1, Ordering::Relaxed);
                    let Some(t) = list.get(i) else { break };
                    let mut acc = Vec::with_capacity(((t.x1 - t.x0) * (t.y1 - t.y0)) as usize);
                    for y in t.y0..t.y1 {
                        for x in t.x0..t.x1 {
                            let mut p = PixelAccum::default();
                            for index in opts.samples.clone() {
                                p.add(render_sample_probed(
                                    scene,
                                    integrator,
                                    opts.seed,
                                    x,
                                    y,
                                    index,
                                    &mut counters,
                                ));
                            }
                            acc.push(p);
                        }
                    }
                    if tx.send((i, acc)).is_err() {
                        break;
                    }
                }
                counters
            }));
        }
        drop(tx);
        let mut done = 0;
        for (i, acc) in rx.iter() {
            let t = list[i];
            let tw = (t.x1 - t.x0) as usize;
            for (row, y) in (t.y0..t.y1).enumerate() {
                let dst = y as usize * w as usize + t.x0 as usize;
                fb.pixels[dst..dst + tw].copy_from_slice(&acc[row * tw..(row + 1) * tw]);
            }
            done += 1;
            progress(done, list.len());
        }
        for worker in workers {
            match worker.join() {
                Ok(c) => total.merge(&c),
                Err(e) => std::panic::resume_unwind(e),
            }
        }
    });
    (fb, total)
}

/// The ordinary render, or with `stats` the counting one, whose counts are printed to stdout
/// (the image is the same bits either way).
pub fn render_maybe_stats(
    stats: bool,
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Framebuffer {
    if !stats {
        return render(scene, integrator, opts, progress);
    }
    let (fb, counters) = render_with_stats(scene, integrator, opts, progress);
    print!("{}", format_stats(scene, &counters, fb.dropped()));
    fb
}

/// The counts as aligned `name  value` lines, with the scene's primitive kinds and the
/// non-finite samples dropped.
pub fn format_stats(scene: &Scene, c: &Counters, dropped: u64) -> String {
    let f = &scene.features;
    let prims = |has: bool| if has { "yes" } else { "no" };
    let mut rows: Vec<(String, String)> = c
        .rows()
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    rows.push(("non-finite samples dropped".into(), dropped.to_string()));
    rows.push((
        "scene has triangles/spheres/disks".into(),
        format!(
            "{}/{}/{}",
            prims(f.has_triangles),
            prims(f.has_spheres),
            prims(f.has_disks)
        ),
    ));
    let width = rows.iter().map(|r| r.0.len()).max().unwrap_or(0);
    let mut out = String::from("stats:\n");
    for (k, v) in rows {
        out.push_str(&format!("  {k:<width$}  {v:>12}\n"));
    }
    out
}

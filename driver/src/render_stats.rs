//! `tessera render --stats`: the tile render of [`crate::render`](mod@crate::render) with a [`Counters`] probe per
//! worker thread, summed at the end.
//!
//! A probe only observes: each sample has the same value as without it, added to its pixel in
//! sample-index order as in the ordinary render, so the image is the same bits. The counts are
//! sums over samples, so they do not depend on the thread count or the tile size either.
use crate::render::{render_span, Framebuffer, RenderOptions, Span};
use std::ops::Range;
use tessera_core::integrator::Counters;
use tessera_core::render::RenderJob;
use tessera_core::scene::Scene;

/// Renders samples `samples` of the selected pixels like [`crate::render::render`] and counts
/// the work done.
pub fn render_with_stats(
    job: &RenderJob,
    samples: Range<u64>,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> (Framebuffer, Counters) {
    let mut fb = Framebuffer::for_job(job);
    let done = render_span(job, opts, &mut fb, Span::Fixed(samples), None, progress);
    (fb, done.probe)
}

/// The ordinary render, or with `stats` the counting one, whose counts are printed to stdout
/// (the image is the same bits either way).
pub fn render_maybe_stats(
    stats: bool,
    job: &RenderJob,
    samples: Range<u64>,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Framebuffer {
    if !stats {
        return crate::render::render(job, samples, opts, progress);
    }
    let (fb, counters) = render_with_stats(job, samples, opts, progress);
    print!("{}", format_stats(job.scene, &counters, fb.dropped()));
    fb
}

/// The counts as aligned `name  value` lines, with the scene's primitive kinds and the
/// non-finite samples dropped.
pub(crate) fn format_stats(scene: &Scene, c: &Counters, dropped: u64) -> String {
    let f = &scene.features;
    let prims = |has: bool| if has { "yes" } else { "no" };
    let mut rows: Vec<(String, String)> = c
        .rows()
        .iter()
        // Medium counts only for scenes that have media.
        .filter(|(k, _)| !scene.media.is_empty() || !(k.contains("medium") || k.contains("null")))
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

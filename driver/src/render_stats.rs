//! `tessera render --stats`: the tile render of [`crate::render`] with a [`Counters`] probe per
//! worker thread ([`crate::render::render_probed`]), summed at the end.
//!
//! Each sample is `render_sample_probed`, which returns the same value as `render_sample` (a
//! probe only observes), added to its pixel in sample-index order as in the ordinary render: the
//! image is the same bits. The counts are sums over samples, so they do not depend on the thread
//! count or the tile size either.
use crate::render::{render, render_probed, Framebuffer, RenderOptions};
use tessera_core::integrator::{Counters, Integrator};
use tessera_core::scene::Scene;

/// Renders the selected pixels like [`crate::render::render`] and counts the work done.
pub fn render_with_stats(
    scene: &Scene,
    integrator: &Integrator,
    opts: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> (Framebuffer, Counters) {
    render_probed(scene, integrator, opts, progress)
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

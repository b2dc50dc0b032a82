//! Path reuse (`path+reuse`, `core/src/integrator/reuse.rs`): the same bits for any thread
//! count, tile size (odd sizes split groups between tiles), sample split and sampler; one sample
//! replayed alone equals the render's; off, it changes nothing; it really shares light.

use std::ops::Range;
use tessera::render::{render, Framebuffer, RenderOptions};
use tessera_core::film::PixelAccum;
use tessera_core::render::RenderJob;
use tessera_scene::LoadedScene;

use crate::scenes;
use crate::support;
use scenes::load;
use support::differing_pixels;

fn render_with(
    l: &LoadedScene,
    samples: Range<u64>,
    threads: usize,
    tile_size: u32,
) -> Framebuffer {
    let opts = RenderOptions {
        threads,
        tile_size,
        pixels: Default::default(),
    };
    let job = RenderJob::new(&l.scene, &l.integrator, l.seed);
    render(&job, samples, &opts, &mut |_, _| {})
}

fn same(a: &Framebuffer, b: &Framebuffer) -> bool {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .all(|(p, q)| p.to_words() == q.to_words())
}

/// cbox at an odd resolution (groups clipped at the right and bottom edges), `reuse` on.
fn reusing(sampler: &str) -> LoadedScene {
    let mut l = load("cbox.xml", &[("res", "23"), ("spp", "4")]);
    l.set_integrator(Some("path+reuse"), None).unwrap();
    l.set_sampler(Some(sampler), 4).unwrap();
    l
}

#[test]
fn same_bits_for_any_threads_tiles_and_split() {
    for sampler in ["independent", "zsobol"] {
        let l = reusing(sampler);
        let reference = render_with(&l, 0..4, 1, 64);
        let lit = reference.pixels.iter().filter(|p| p.sum[0] > 0.0).count();
        assert!(lit > reference.pixels.len() / 2, "{sampler}: {lit} lit");
        for (threads, tile) in [(2, 1), (2, 5), (3, 7), (2, 16), (8, 3)] {
            let fb = render_with(&l, 0..4, threads, tile);
            assert!(
                same(&reference, &fb),
                "{sampler}: {threads} threads, tile {tile}"
            );
        }
        // Sample ranges rendered apart hold the same per-sample values: the second half alone
        // equals the second half of a whole render's accumulators minus the first half.
        let first = render_with(&l, 0..2, 2, 5);
        let second = render_with(&l, 2..4, 3, 7);
        for ((w, a), b) in reference
            .pixels
            .iter()
            .zip(&first.pixels)
            .zip(&second.pixels)
        {
            let mut m = *a;
            m.merge(b);
            assert_eq!(m.count, w.count);
            for k in 0..3 {
                let (x, y) = (m.sum[k], w.sum[k]);
                assert!((x - y).abs() <= 1e-12 * x.abs().max(y.abs()) + 1e-300);
            }
        }
    }
}

#[test]
fn one_sample_replayed_alone_matches_the_render() {
    for sampler in ["independent", "zsobol"] {
        let l = reusing(sampler);
        for index in [0u64, 3] {
            let fb = render_with(&l, index..index + 1, 2, 5);
            for (x, y) in [
                (0, 0),
                (1, 0),
                (0, 1),
                (1, 1),
                (22, 22),
                (22, 7),
                (13, 22),
                (9, 4),
            ] {
                let c = RenderJob::new(&l.scene, &l.integrator, l.seed).sample(x, y, index);
                let mut want = PixelAccum::default();
                want.add(c);
                assert_eq!(
                    fb.at(x, y).to_words(),
                    want.to_words(),
                    "{sampler} ({x}, {y}) #{index}"
                );
            }
        }
    }
}

#[test]
fn reuse_shares_light_and_off_changes_nothing() {
    let mut l = load("cbox.xml", &[("res", "16"), ("spp", "2")]);
    let plain = render_with(&l, 0..2, 2, 16);
    // `path` named explicitly (reuse off) is the file's integrator, bit for bit.
    l.set_integrator(Some("path"), None).unwrap();
    assert!(same(&plain, &render_with(&l, 0..2, 2, 5)));
    // With reuse, most pixels change (their indirect light now comes from four paths).
    l.set_integrator(Some("path+reuse"), None).unwrap();
    let shared = render_with(&l, 0..2, 2, 16);
    let changed = differing_pixels(&plain, &shared);
    assert!(
        changed > plain.pixels.len() / 2,
        "only {changed} pixels changed"
    );
    // Where reuse cannot apply (max_depth 2: no second vertex reflects), it is plain rendering.
    let mut direct = load(
        "cbox.xml",
        &[("res", "16"), ("spp", "2"), ("max_depth", "2")],
    );
    let want = render_with(&direct, 0..2, 2, 16);
    direct.set_integrator(Some("path+reuse"), None).unwrap();
    assert!(same(&want, &render_with(&direct, 0..2, 2, 7)));
}

#[test]
fn reuse_needs_a_path_tracer() {
    let mut l = load("cbox.xml", &[("res", "8"), ("spp", "1")]);
    let e = l.set_integrator(Some("direct+reuse"), None).unwrap_err();
    assert!(e.contains("needs a path tracer"), "{e}");
}

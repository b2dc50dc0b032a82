//! The rendered image is a function of the scene, the seed and the sample range only: the same
//! bits for any thread count and any tile size; sample ranges rendered apart merge into the
//! whole; one sample replayed alone equals what the full render accumulated for it.

use std::ops::Range;
use tessera::render::{render, Framebuffer, RenderOptions};
use tessera_core::camera::Filter;
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
    seed: u64,
) -> Framebuffer {
    let opts = RenderOptions {
        threads,
        tile_size,
        pixels: Default::default(),
    };
    let job = RenderJob::new(&l.scene, &l.integrator, seed);
    let mut last = (0, 0);
    let fb = render(&job, samples, &opts, &mut |done, total| {
        assert!(done > last.0 && done <= total);
        last = (done, total);
    });
    assert_eq!(last.0, last.1, "progress did not reach every tile");
    fb
}

/// Asserts `b` is bit for bit the same image as `a` (naming the first differing pixel).
fn assert_same_bits(a: &Framebuffer, b: &Framebuffer, what: &str) {
    assert_eq!((a.width, a.height), (b.width, b.height), "{what}: size");
    assert_eq!(a.pixels.len(), (a.width * a.height) as usize, "{what}");
    assert_eq!(a.pixels.len(), b.pixels.len(), "{what}");
    for (i, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        assert!(
            p.to_words() == q.to_words(),
            "{what}: pixel ({}, {}) differs: {p:?} vs {q:?}",
            i as u32 % a.width,
            i as u32 / a.width
        );
    }
    // The splatted sums, which the image is made from when the filter splats.
    let splats = |f: &Framebuffer| {
        f.splats
            .as_ref()
            .map(|s| s.sums.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
    };
    assert!(splats(a) == splats(b), "{what}: splatted sums differ");
    let image = |f: &Framebuffer| {
        f.rgb()
            .concat()
            .iter()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>()
    };
    assert!(image(a) == image(b), "{what}: image differs");
}

/// The image is not trivially black / empty (so equality means something).
fn assert_nontrivial(fb: &Framebuffer, spp: u64) {
    let lit = fb
        .pixels
        .iter()
        .filter(|p| p.sum.iter().any(|&s| s > 0.0))
        .count();
    assert!(lit > fb.pixels.len() / 2, "only {lit} pixels are lit");
    for p in &fb.pixels {
        assert_eq!(p.count + p.dropped, spp);
    }
}

#[test]
fn cbox_same_bits_for_any_threads_and_tile_size() {
    let l = load("cbox.xml", &[("res", "24"), ("spp", "4")]);
    assert_eq!(l.spp, 4);
    assert!(
        matches!(l.scene.filter, Filter::Gaussian(_)),
        "want the default gaussian filter"
    );
    assert!(l.scene.splat.is_some(), "the gaussian filter splats");
    assert_eq!((l.scene.camera.width, l.scene.camera.height), (24, 24));
    let reference = render_with(&l, 0..l.spp, 1, 1, l.seed);
    assert_nontrivial(&reference, l.spp);
    for threads in [1, 2, 3, 8] {
        for tile in [1, 5, 8, 16, 64] {
            let fb = render_with(&l, 0..l.spp, threads, tile, l.seed);
            assert_same_bits(
                &reference,
                &fb,
                &format!("cbox, {threads} threads, tile size {tile}"),
            );
        }
    }
}

#[test]
fn cs500_spheres_same_bits_for_two_threads() {
    let l = load("cs500_spheres.xml", &[("res", "24"), ("spp", "4")]);
    let one = render_with(&l, 0..l.spp, 1, 32, l.seed);
    assert_nontrivial(&one, l.spp);
    let two = render_with(&l, 0..l.spp, 2, 7, l.seed);
    assert_same_bits(&one, &two, "cs500_spheres, 2 threads vs 1");
}

#[test]
fn split_sample_ranges_merge_into_the_whole() {
    let l = load("cbox.xml", &[("res", "24"), ("spp", "4")]);
    let whole = render_with(&l, 0..4, 2, 8, l.seed);
    let first = render_with(&l, 0..2, 2, 8, l.seed);
    let second = render_with(&l, 2..4, 3, 5, l.seed);
    assert_nontrivial(&whole, 4);
    for (i, ((w, a), b)) in whole
        .pixels
        .iter()
        .zip(&first.pixels)
        .zip(&second.pixels)
        .enumerate()
    {
        let mut m = *a;
        m.merge(b);
        assert_eq!((m.count, m.dropped), (w.count, w.dropped), "pixel {i}");
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()) + 1e-300;
        for k in 0..3 {
            assert!(close(m.sum[k], w.sum[k]), "pixel {i}: sum {m:?} vs {w:?}");
            assert!(
                close(m.sum_sq[k], w.sum_sq[k]),
                "pixel {i}: sum_sq {m:?} vs {w:?}"
            );
        }
        let (mm, wm) = (m.mean(), w.mean());
        for k in 0..3 {
            let (x, y) = (mm[k] as f64, wm[k] as f64);
            assert!(
                (x - y).abs() <= 1e-6 * x.abs().max(y.abs()) + 1e-30,
                "pixel {i}: mean {mm:?} vs {wm:?}"
            );
        }
    }
}

#[test]
fn one_sample_replayed_alone_matches_the_render() {
    let l = load("cbox.xml", &[("res", "24"), ("spp", "1")]);
    let pixels = [(0, 0), (12, 12), (23, 5), (3, 20), (17, 1), (23, 23)];
    // Sample index 0 (spp = 1) and a later single sample (index 7 of a longer render).
    for index in [0u64, 7] {
        let fb = render_with(&l, index..index + 1, 2, 5, l.seed);
        for (x, y) in pixels {
            let c = RenderJob::new(&l.scene, &l.integrator, l.seed).sample(x, y, index);
            let acc = fb.at(x, y);
            let mut want = PixelAccum::default();
            want.add(c);
            assert_eq!(
                acc.to_words(),
                want.to_words(),
                "pixel ({x}, {y}) sample {index}: render {acc:?}, replay {c:?}"
            );
            assert_eq!(acc.count, 1, "pixel ({x}, {y}) sample {index} was dropped");
            for k in 0..3 {
                assert_eq!(acc.sum[k].to_bits(), (c[k] as f64).to_bits());
            }
        }
    }
}

#[test]
fn different_seeds_give_different_images() {
    let l = load("cbox.xml", &[("res", "24"), ("spp", "4")]);
    let a = render_with(&l, 0..4, 2, 16, l.seed);
    let b = render_with(&l, 0..4, 2, 16, l.seed.wrapping_add(1));
    let differing = differing_pixels(&a, &b);
    assert!(
        differing > a.pixels.len() / 2,
        "only {differing} of {} pixels differ between seeds {} and {}",
        a.pixels.len(),
        l.seed,
        l.seed.wrapping_add(1)
    );
    // Same seed, different sample ranges: also different (the index feeds the streams).
    let c = render_with(&l, 4..8, 2, 16, l.seed);
    assert!(a
        .pixels
        .iter()
        .zip(&c.pixels)
        .any(|(p, q)| p.to_words() != q.to_words()));
}

//! `--stats` and `--debug-pixel` observe the render without changing it: the counting render
//! gives the same bits as the ordinary one and the same counts for any thread count and tile
//! size; the debug trace prints exactly the values the render accumulates.
use std::path::Path;
use std::process::Command;
use tessera::render::{render, render_span, Framebuffer, RenderOptions, Span};
use tessera::render_stats::render_with_stats;
use tessera_core::integrator::{Counters, NoProbe};
use tessera_core::render::RenderJob;
use tessera_scene::LoadedScene;

const BIN: &str = env!("CARGO_BIN_EXE_tessera");

use crate::scenes;
use scenes::{load, scene_path};

fn opts(threads: usize, tile_size: u32) -> RenderOptions {
    RenderOptions {
        threads,
        tile_size,
        ..Default::default()
    }
}

/// `l`'s own samples and seed, rendered on `threads` threads in tiles of `tile_size`.
fn plain(l: &LoadedScene, threads: usize, tile_size: u32) -> Framebuffer {
    let job = RenderJob::new(&l.scene, &l.integrator, l.seed);
    render(&job, 0..l.spp, &opts(threads, tile_size), &mut |_, _| {})
}

fn stats(l: &LoadedScene, threads: usize, tile_size: u32) -> (Framebuffer, Counters) {
    let job = RenderJob::new(&l.scene, &l.integrator, l.seed);
    render_with_stats(&job, 0..l.spp, &opts(threads, tile_size), &mut |_, _| {})
}

#[test]
fn stats_render_is_the_same_image_with_the_same_counts_for_any_threads() {
    for (name, integrator) in [
        ("cbox.xml", None),
        ("cbox.xml", Some("direct")),
        ("cs500_spheres.xml", None),
        ("veach_mis.xml", None),
    ] {
        let mut l = load(name, &[("res", "24"), ("spp", "3")]);
        l.set_integrator(integrator, None).unwrap();
        let plain = plain(&l, 2, 7);
        assert!(plain.pixels.iter().any(|p| p.sum[0] > 0.0), "{name}");
        let (fb, reference) = stats(&l, 1, 32);
        assert!(
            fb == plain,
            "{name} {integrator:?}: --stats changed the image"
        );
        assert_eq!(reference.samples, 24 * 24 * 3);
        assert!(reference.shadow_rays > 0 && reference.continuation_rays > 0);
        for (threads, tile) in [(2, 5), (3, 16), (8, 1)] {
            let (fb, c) = stats(&l, threads, tile);
            assert!(
                fb == plain,
                "{name}: image with {threads} threads, tile {tile}"
            );
            assert_eq!(
                c, reference,
                "{name}: counts with {threads} threads, tile {tile}"
            );
        }
    }
}

#[test]
fn counters_merge_adds_every_field() {
    let l = load("cbox.xml", &[("res", "8"), ("spp", "2")]);
    let (_, c) = stats(&l, 1, 8);
    let mut twice = c;
    twice.merge(&c);
    for ((name, a), (_, b)) in c.rows().iter().zip(twice.rows()) {
        assert_eq!(2 * a, b, "{name}");
    }
    assert_ne!(twice, c);
}

/// The `[a, b, c]` after `prefix` on each line that has it, parsed back to exact f32s.
fn triples(text: &str, prefix: &str) -> Vec<[f32; 3]> {
    text.lines()
        .filter_map(|l| l.trim_start().strip_prefix(prefix))
        .map(|rest| {
            let inner = &rest[rest.find('[').unwrap() + 1..rest.find(']').unwrap()];
            let v: Vec<f32> = inner.split(", ").map(|s| s.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

fn debug_pixel(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(BIN)
        .arg("render")
        .arg(scene_path("cbox.xml"))
        .args(["-D", "res=24", "--spp", "5"])
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn debug_pixel_prints_exactly_what_the_render_accumulates() {
    let mut l = load("cbox.xml", &[("res", "24")]);
    l.spp = 5;
    let fb = plain(&l, 2, 8);
    for (x, y) in [(12, 12), (3, 20), (23, 0)] {
        let (code, out, err) = debug_pixel(&["--debug-pixel", &format!("{x},{y}")]);
        assert_eq!(code, 0, "{err}");
        let values = triples(&out, "value:");
        assert_eq!(values.len(), 5, "{out}");
        for (i, v) in values.iter().enumerate() {
            let c = RenderJob::new(&l.scene, &l.integrator, l.seed).sample(x, y, i as u64);
            assert_eq!(
                v.map(f32::to_bits),
                c.to_array().map(f32::to_bits),
                "({x}, {y}) sample {i}"
            );
        }
        let mean = triples(&out, "pixel mean:");
        assert_eq!(mean, vec![fb.at(x, y).mean()], "({x}, {y}):\n{out}");
        assert!(
            out.contains("vertex 1: p ") && out.contains("path ends: "),
            "{out}"
        );
        // One sample alone: the same value as in the full trace.
        let (code, one, _) = debug_pixel(&["--debug-pixel", &format!("{x},{y},3")]);
        assert_eq!(code, 0);
        assert_eq!(triples(&one, "value:"), vec![values[3]]);
        assert!(!one.contains("pixel mean"));
    }
    // Control: the parse is exact, so another pixel's value does not pass for this one.
    let (_, out, _) = debug_pixel(&["--debug-pixel", "12,12,0"]);
    let c = RenderJob::new(&l.scene, &l.integrator, l.seed).sample(12, 13, 0);
    assert_ne!(triples(&out, "value:"), vec![c.to_array()]);
}

#[test]
fn debug_pixel_rejects_what_is_outside_the_render() {
    for (arg, want) in [
        ("24,0", "outside the 24x24 image"),
        ("0,30", "outside the 24x24 image"),
        ("1,1,5", "outside the render's samples 0..5"),
        ("1", "expected x,y or x,y,sample"),
        ("1,2,3,4", "expected x,y or x,y,sample"),
        ("-1,2", "expected x,y or x,y,sample"),
        ("a,b", "expected x,y or x,y,sample"),
    ] {
        let (code, out, err) = debug_pixel(&[&format!("--debug-pixel={arg}")]);
        assert_eq!(code, 2, "{arg}: {err}");
        assert!(err.contains(want), "{arg}: {err}");
        assert!(out.is_empty(), "{arg}: {out}");
        assert!(!err.contains("panicked"), "{arg}: {err}");
    }
}

#[test]
fn stats_flag_prints_counts_and_writes_the_same_image() {
    let dir = std::env::temp_dir().join(format!("tessera-probe-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (a, b) = (dir.join("plain.pfm"), dir.join("stats.pfm"));
    let run = |out: &Path, extra: &[&str]| {
        Command::new(BIN)
            .arg("render")
            .arg(scene_path("cbox.xml"))
            .args(["-D", "res=16", "--spp", "2", "-q", "-o"])
            .arg(out)
            .args(extra)
            .output()
            .unwrap()
    };
    let plain = run(&a, &[]);
    assert!(plain.status.success());
    assert!(plain.stdout.is_empty());
    let with = run(&b, &["--stats"]);
    assert!(with.status.success());
    let text = String::from_utf8(with.stdout).unwrap();
    let line = |name: &str| -> u64 {
        let l = text
            .lines()
            .find(|l| l.trim_start().starts_with(name))
            .unwrap_or_else(|| panic!("no {name} in\n{text}"));
        l.split_whitespace().last().unwrap().parse().unwrap()
    };
    assert_eq!(line("camera rays"), 16 * 16 * 2);
    assert!(line("shadow rays") > 0);
    assert_eq!(line("env lookups"), 0);
    assert_eq!(line("non-finite samples dropped"), 0);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Each pixel's ray count (what adaptive sampling prices its samples by) is the rays its
/// samples cast: summed over the image, the `--stats` counts of camera, continuation and shadow
/// rays, also where the ordinary render finishes escaping camera rays in batches (the
/// environment map of `envmap.xml`), which the counting render does not; every sample casts at
/// least its camera ray, and a pixel whose samples all escape casts exactly that. Only per-pixel
/// targets (adaptive passes) count; the same image otherwise.
#[test]
fn pixels_count_the_rays_their_samples_cast() {
    for (name, integrator) in [
        ("cbox.xml", None),
        ("cbox.xml", Some("direct")),
        ("veach_mis.xml", None),
        ("envmap.xml", None),
    ] {
        let mut l = load(name, &[("res", "24"), ("spp", "3")]);
        l.set_integrator(integrator, None).unwrap();
        let job = RenderJob::new(&l.scene, &l.integrator, l.seed);
        let mut fb = Framebuffer::for_job(&job);
        let targets = vec![l.spp; fb.pixels.len()];
        let span = Span::Targets(&targets);
        render_span::<NoProbe>(&job, &opts(2, 7), &mut fb, span, None, &mut |_, _| {});
        let (plain_fb, c) = stats(&l, 1, 32);
        let rays: u64 = fb.pixels.iter().map(|p| p.rays).sum();
        assert_eq!(
            rays,
            c.camera_rays + c.continuation_rays + c.shadow_rays,
            "{name} {integrator:?}"
        );
        assert!(rays > 2 * c.camera_rays, "{name}: {rays}");
        assert!(fb.pixels.iter().all(|p| p.rays >= p.count + p.dropped));
        if name == "envmap.xml" {
            let sky_only = fb.pixels.iter().filter(|p| p.rays == p.count).count();
            assert!(sky_only > 24, "{name}: {sky_only} pixels see only the sky");
        }
        // The control: the plain render counts nothing, and its sums are the same.
        assert!(plain_fb.pixels.iter().all(|p| p.rays == 0), "{name}");
        for p in &mut fb.pixels {
            p.rays = 0;
        }
        assert!(
            fb.pixels == plain_fb.pixels,
            "{name}: the counting render's sums"
        );
    }
}

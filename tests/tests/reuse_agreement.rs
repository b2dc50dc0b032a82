//! Path reuse (`path+reuse`) converges to the image plain path tracing converges to, region by
//! region, on scenes with Lambertian second vertices (cbox), glossy ones that fall back to plain
//! paths (veach_mis) and a mix of smooth, delta and layered materials (materials).
//!
//! Reuse correlates the pixels of a group (4x2), so a render's per-pixel variances do not give its
//! region means' variance. Each side is therefore `K` renders with different seeds, and each
//! 8x8-pixel region's `K` means are compared by Welch's t-test. Significance 0.01,
//! Sidak-corrected over all regions and channels of a test.
//!
//! Adaptive passes share light only among the pixels of a group that take each sample index;
//! that estimator is checked with fixed targets that differ inside every group.
use tessera::render::{render_span, Framebuffer, RenderOptions, Span};
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;
use tessera_lab::stats::{sidak_alpha, welch_test, Moments};
use tessera_scene::LoadedScene;
use tessera_tests::{load_file, render_loaded};

const RES: u32 = 64;
const BLOCK: u32 = 8;
const K: u64 = 16;

/// Each region's mean (row-major regions, then channels) for one render.
fn region_means(fb: &Framebuffer) -> Vec<[f64; 3]> {
    let n = RES / BLOCK;
    let mut out = vec![[0.0; 3]; (n * n) as usize];
    for y in 0..RES {
        for x in 0..RES {
            let p = fb.at(x, y);
            let r = &mut out[((y / BLOCK) * n + x / BLOCK) as usize];
            for (k, v) in r.iter_mut().enumerate() {
                *v += p.sum[k] / p.count as f64 / (BLOCK * BLOCK) as f64;
            }
        }
    }
    out
}

/// Per region and channel, the moments of its mean over `K` seeds (from `seed0`), each render
/// scaled by `scale`.
fn replicates(file: &str, integrator: &str, spp: u64, seed0: u64, scale: f64) -> Vec<[Moments; 3]> {
    replicates_by(file, integrator, seed0, scale, &|l, seed| {
        render_loaded(l, spp, seed)
    })
}

/// [`replicates`] with renders made by `render(scene, seed)`.
fn replicates_by(
    file: &str,
    integrator: &str,
    seed0: u64,
    scale: f64,
    render: &dyn Fn(&LoadedScene, u64) -> Framebuffer,
) -> Vec<[Moments; 3]> {
    let mut loaded = load_file(file, &[("res", "64"), ("rfilter", "box")]);
    loaded
        .set_integrator(Some(integrator), None)
        .expect("path tracer");
    let mut out: Vec<[Moments; 3]> = Vec::new();
    for s in 0..K {
        let fb = render(&loaded, seed0 + s);
        assert_eq!(fb.dropped(), 0, "{file} {integrator}: dropped samples");
        let means = region_means(&fb);
        out.resize_with(means.len(), Default::default);
        for (o, m) in out.iter_mut().zip(means) {
            for k in 0..3 {
                o[k].push(m[k] * scale);
            }
        }
    }
    out
}

/// The smallest p-value over regions and channels of Welch's test between `a` and `b`.
fn worst(a: &[[Moments; 3]], b: &[[Moments; 3]]) -> (f64, String) {
    let mut worst = (1.0, String::new());
    for (i, (ra, rb)) in a.iter().zip(b).enumerate() {
        for k in 0..3 {
            let t = welch_test(ra[k].summary(), rb[k].summary());
            if t.p_value < worst.0 {
                let n = RES / BLOCK;
                worst = (
                    t.p_value,
                    format!(
                        "region ({}, {}) channel {k}, t = {:.2}",
                        i as u32 % n,
                        i as u32 / n,
                        t.t
                    ),
                );
            }
        }
    }
    worst
}

fn agrees(file: &str, spp: u64) {
    let reuse = replicates(file, "path+reuse", spp, 100, 1.0);
    let plain = replicates(file, "path", spp, 200, 1.0);
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst(&reuse, &plain);
    eprintln!("{file}: reuse vs plain: worst p = {p:.3e} at {what}");
    assert!(
        p >= alpha,
        "{file}: reuse vs plain: p = {p:.3e} < {alpha:.3e} at {what}"
    );
}

#[test]
fn reuse_agrees_with_plain_paths_on_the_cornell_box() {
    agrees("cbox.xml", 32);
}

#[test]
fn reuse_agrees_with_plain_paths_on_veach_mis() {
    agrees("veach_mis.xml", 16);
}

#[test]
fn reuse_agrees_with_plain_paths_on_materials() {
    agrees("materials.xml", 16);
}

/// Diffuse spheres and floor under a sky with a sun, nothing else: every second vertex shares
/// light that the map's compensated tables and BSDF sampling found together.
#[test]
fn reuse_agrees_with_plain_paths_under_an_environment_map() {
    for integrator in ["path", "path+reuse"] {
        let mut l = load_file("envmap.xml", &[("res", "8")]);
        l.set_integrator(Some(integrator), None)
            .expect("path tracer");
        assert!(l.scene.environment_compensated(), "{integrator}");
    }
    agrees("envmap.xml", 16);
}

/// Targets that differ inside every group (8 to 40 samples, fixed in advance): at each
/// sample index only the pixels that take it share, weighted over those pixels' densities.
#[test]
fn reuse_with_uneven_targets_agrees_with_plain_paths() {
    let targets: Vec<u64> = (0..(RES * RES) as u64)
        .map(|i| [8, 32, 16, 24][(i % 2 + i / RES as u64 % 2 * 2) as usize] + (i / 7 % 2) * 8)
        .collect();
    let uneven = replicates_by("cbox.xml", "path+reuse", 500, 1.0, &|l, seed| {
        let opts = RenderOptions {
            threads: 2,
            tile_size: 16,
            ..Default::default()
        };
        let job = RenderJob::new(&l.scene, &l.integrator, seed);
        let mut fb = Framebuffer::new(RES, RES);
        let span = Span::Targets(&targets);
        render_span::<NoProbe>(&job, &opts, &mut fb, span, None, &mut |_, _| {});
        fb
    });
    let plain = replicates("cbox.xml", "path", 32, 600, 1.0);
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    let (p, what) = worst(&uneven, &plain);
    eprintln!("cbox: reuse with uneven targets vs plain: worst p = {p:.3e} at {what}");
    assert!(p >= alpha, "p = {p:.3e} < {alpha:.3e} at {what}");
}

/// The comparison has power: reuse renders made 2% brighter are rejected.
#[test]
fn comparison_rejects_a_two_percent_bias() {
    let reuse = replicates("cbox.xml", "path+reuse", 32, 300, 1.02);
    let plain = replicates("cbox.xml", "path", 32, 400, 1.0);
    let (p, what) = worst(&reuse, &plain);
    let alpha = sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3);
    assert!(
        p < alpha,
        "a 2% bias went unnoticed (p = {p:.3e} at {what})"
    );
}

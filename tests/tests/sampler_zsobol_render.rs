//! Renders with the zsobol sampler are unbiased: closed-form scenes (from
//! `tessera_tests::analytic_scenes`) rendered with `R` different seeds, each seed's image mean one independent estimate (the
//! seed enters every hash, so the randomizations are independent), t-tested across seeds
//! against the analytic value at significance 0.01, Sidak-corrected over every test here.
//! The samples within one pixel are not independent (that is the point of the sampler), so
//! their sample variance is not the estimate's variance; the spread across seeds is. A control
//! shows the test rejects a reference 2% off, and the image is also bit for bit the same for
//! any thread count and tile size and when its samples are rendered in two ranges.
use tessera::render::{render_span, Framebuffer, RenderOptions, Span};
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;
use tessera_core::sampling::SamplerKind;
use tessera_lab::stats::sidak_alpha;
use tessera_scene::LoadedScene;
use tessera_tests::analytic_scenes::{closed_sphere, furnace_box, sphere_light};
use tessera_tests::{load_xml, t_test_f32};

/// Seeds per case.
const SEEDS: u64 = 40;
/// Samples per pixel per seed.
const SPP: u64 = 64;

/// (label, scene, integrator, max_depth, expected RGB).
fn cases() -> Vec<(&'static str, String, &'static str, i64, [f64; 3])> {
    let a = [0.3f64, 0.5, 0.7];
    let (l, r, h) = (10.0f64, 0.5f64, 3.0f64);
    let light = [0.7f64, 0.5, 0.3].map(|a| a * l * r * r / (h * h));
    let closed_sphere = || closed_sphere(30.0, 4);
    vec![
        (
            "closed sphere path_mis",
            closed_sphere(),
            "path_mis",
            -1,
            a.map(|a| 1.0 / (1.0 - a)),
        ),
        (
            "closed sphere path_mats depth 3",
            closed_sphere(),
            "path_mats",
            3,
            a.map(|a| 1.0 + a + a * a),
        ),
        (
            "sphere light path_mis",
            sphere_light(),
            "path_mis",
            2,
            light,
        ),
        (
            "sphere light path_mats",
            sphere_light(),
            "path_mats",
            2,
            light,
        ),
        (
            "furnace box path_ems",
            furnace_box(),
            "path_ems",
            -1,
            a.map(|a| 1.0 / (1.0 - a)),
        ),
    ]
}

fn load_zsobol(xml: &str, integrator: &str, depth: i64, spp: u64) -> LoadedScene {
    let mut l = load_xml(xml, &[]);
    l.set_integrator(Some(integrator), Some(depth))
        .expect("known integrator");
    l.set_sampler(Some("zsobol"), spp).expect("known sampler");
    assert_eq!(l.scene.sampler, SamplerKind::ZSobol { log2_spp: 6 });
    l
}

/// Samples `samples` of `l` with `seed`, added to `fb`, on `threads` threads in tiles of `tile`.
fn render_into(
    l: &LoadedScene,
    fb: &mut Framebuffer,
    samples: std::ops::Range<u64>,
    threads: usize,
    tile: u32,
    seed: u64,
) {
    let opts = RenderOptions {
        threads,
        tile_size: tile,
        ..Default::default()
    };
    let job = RenderJob::new(&l.scene, &l.integrator, seed);
    render_span::<NoProbe>(&job, &opts, fb, Span::Fixed(samples), None, &mut |_, _| {});
}

/// A new render of samples `samples` of `l` (see [`render_into`]).
fn render(
    l: &LoadedScene,
    samples: std::ops::Range<u64>,
    threads: usize,
    tile: u32,
    seed: u64,
) -> Framebuffer {
    let mut fb = Framebuffer::new(l.scene.camera.width, l.scene.camera.height);
    render_into(l, &mut fb, samples, threads, tile, seed);
    fb
}

/// Image mean per channel.
fn image_mean(fb: &Framebuffer) -> [f64; 3] {
    let mut m = [0.0; 3];
    for p in &fb.pixels {
        assert_eq!(p.dropped, 0);
        for (k, v) in m.iter_mut().enumerate() {
            *v += p.sum[k] / p.count as f64 / fb.pixels.len() as f64;
        }
    }
    m
}

/// Two-sided p-value of the mean of `xs` against `expected`, by
/// [`t_test_f32`](tessera_tests::t_test_f32) (f32 rendering).
fn p_value(xs: &[f64], expected: f64) -> f64 {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    t_test_f32(n, mean, var, expected).1
}

#[test]
fn zsobol_renders_are_unbiased() {
    let cases = cases();
    let alpha = sidak_alpha(0.01, cases.len() * 3);
    let mut control_rejected = false;
    for (label, xml, integ, depth, expected) in cases {
        let l = load_zsobol(&xml, integ, depth, SPP);
        let means: Vec<[f64; 3]> = (0..SEEDS)
            .map(|seed| image_mean(&render(&l, 0..SPP, 2, 16, 1000 + seed)))
            .collect();
        for k in 0..3 {
            let xs: Vec<f64> = means.iter().map(|m| m[k]).collect();
            let p = p_value(&xs, expected[k]);
            eprintln!("{label} channel {k}: p = {p:.3e}");
            assert!(
                p >= alpha,
                "{label} channel {k}: mean over seeds vs {} p = {p:.3e}",
                expected[k]
            );
            control_rejected |= p_value(&xs, expected[k] * 1.02) < alpha;
        }
    }
    assert!(control_rejected, "no case rejects a reference 2% off");
}

#[test]
fn zsobol_images_do_not_depend_on_threads_tiles_or_splits() {
    let l = load_zsobol(&closed_sphere(30.0, 4), "path_mis", -1, 64);
    let whole = render(&l, 0..64, 1, 16, 5);
    assert!(image_mean(&whole)[0] > 0.5);
    for (threads, tile) in [(2, 1), (3, 3), (4, 2)] {
        let fb = render(&l, 0..64, threads, tile, 5);
        assert_eq!(fb, whole, "{threads} threads, tile {tile}");
    }
    let mut split = Framebuffer::new(whole.width, whole.height);
    for r in [0..20, 20..64] {
        render_into(&l, &mut split, r, 2, 3, 5);
    }
    assert_eq!(split, whole, "samples rendered in two ranges");
    // Another seed gives another image.
    let other = render(&l, 0..64, 2, 16, 6);
    assert_ne!(other, whole);
}

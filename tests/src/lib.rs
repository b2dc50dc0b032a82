//! Shared helpers of Tessera's integration and statistical tests: render a scene given as XML
//! text, and turn per-pixel sums into the numbers statistical tests need.
use std::path::{Path, PathBuf};
use tessera::render::{render, Framebuffer, RenderOptions};
use tessera_scene::{load_scene, load_scene_str, LoadedScene};

/// The repository's `scenes/` folder.
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// Loads a scene from XML text (relative paths resolve in `scenes/`).
pub fn load_xml(xml: &str, defines: &[(&str, &str)]) -> LoadedScene {
    let defines: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    load_scene_str(xml, &scenes_dir().join("inline-test.xml"), &defines)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Loads a scene file from `scenes/`.
pub fn load_file(name: &str, defines: &[(&str, &str)]) -> LoadedScene {
    let defines: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    load_scene(&scenes_dir().join(name), &defines).unwrap_or_else(|e| panic!("{e}"))
}

/// Loads scene file `name` from `scenes/` with its text changed by `edit` (relative paths still
/// resolve beside it). Panics when the edit changes nothing: the scene file no longer holds
/// what the test edits, and the test needs updating.
pub fn load_file_edited(
    name: &str,
    edit: impl FnOnce(&str) -> String,
    defines: &[(&str, &str)],
) -> LoadedScene {
    let path = scenes_dir().join(name);
    let text = std::fs::read_to_string(&path).expect("scene file");
    let edited = edit(&text);
    assert_ne!(
        text, edited,
        "{name}: the edit changed nothing; update this test"
    );
    let defines: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    load_scene_str(&edited, &path, &defines).unwrap_or_else(|e| panic!("{e}"))
}

/// Renders a loaded scene with `spp` samples on 2 threads, its filter applied by importance
/// sampling (see `render_two_threads`).
pub fn render_loaded(l: &LoadedScene, spp: u64, seed: u64) -> Framebuffer {
    render_two_threads(&l.scene, &l.integrator, spp, seed)
}

/// Renders with `spp` samples on 2 threads. The statistical tests read each pixel's own sums
/// ([`region_stats`]), which are independent samples of the pixel's value only when the filter
/// is applied by importance sampling (`--filter-sampling`); a scene that splats is rendered that
/// way (splatting itself is tested against Mitsuba in `splat_agreement.rs`).
fn render_two_threads(
    scene: &tessera_core::scene::Scene,
    integrator: &tessera_core::integrator::Integrator,
    spp: u64,
    seed: u64,
) -> Framebuffer {
    let opts = RenderOptions {
        threads: 2,
        tile_size: 16,
        pixels: Default::default(),
    };
    let sampled;
    let scene = match scene.splat {
        None => scene,
        Some(_) => {
            let mut s = scene.clone();
            s.splat = None;
            sampled = s;
            &sampled
        }
    };
    let job = tessera_core::render::RenderJob::new(scene, integrator, seed);
    render(&job, 0..spp, &opts, &mut |_, _| {})
}

/// Mean and variance of the mean of a block of pixels, per channel. Pixels are strata: the
/// variance is the sum of each pixel's sample variance over its sample count, over the pixel
/// count squared.
pub fn region_stats(fb: &Framebuffer, x0: u32, y0: u32, w: u32, h: u32) -> [(f64, f64); 3] {
    assert!(
        fb.splats.is_none(),
        "region statistics need pixels with their own samples: render with filter sampling"
    );
    let mut out = [(0.0, 0.0); 3];
    let n_pix = (w * h) as f64;
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            let p = fb.at(x, y);
            let n = p.count as f64;
            for (k, o) in out.iter_mut().enumerate() {
                let mean = p.sum[k] / n;
                let var = ((p.sum_sq[k] - n * mean * mean) / (n - 1.0)).max(0.0);
                o.0 += mean / n_pix;
                o.1 += var / n / (n_pix * n_pix);
            }
        }
    }
    out
}

/// Two-sided p-value of a z statistic.
pub fn z_p_value(z: f64) -> f64 {
    use statrs::distribution::{ContinuousCDF, Normal};
    let n = Normal::new(0.0, 1.0).expect("standard normal");
    2.0 * n.sf(z.abs())
}

/// Two-sided Student t-test of a sample mean (`n` samples, sample variance `var`) against
/// `expected`: `(t, p-value)`. The renderer computes in f32, so its answer carries a few ulps of
/// rounding that no number of samples removes: `(4 f32 ulps of the reference)^2` joins the
/// squared standard error, holding near-zero-variance estimators (BSDF sampling in a furnace,
/// delta lights) to f32 precision rather than beyond it.
pub fn t_test_f32(n: f64, mean: f64, var: f64, expected: f64) -> (f64, f64) {
    use statrs::distribution::{ContinuousCDF, StudentsT};
    let ulp = (expected as f32).abs() as f64 * f32::EPSILON as f64;
    let se = (var / n + (4.0 * ulp).powi(2)).sqrt();
    let t = (mean - expected) / se;
    let dist = StudentsT::new(0.0, 1.0, n - 1.0).expect("dof > 0");
    (t, 2.0 * dist.sf(t.abs()))
}

/// Asserts that each channel of pixel `p` matches `expected` by [`t_test_f32`] at `alpha`.
pub fn assert_pixel_matches(
    label: &str,
    p: &tessera_core::film::PixelAccum,
    expected: [f64; 3],
    alpha: f64,
) {
    assert_eq!(p.dropped, 0, "{label}: non-finite samples");
    for (k, expected) in expected.into_iter().enumerate() {
        let (n, mean) = (p.count as f64, p.sum[k] / p.count as f64);
        let var = ((p.sum_sq[k] - n * mean * mean) / (n - 1.0)).max(0.0);
        let (t, p_value) = t_test_f32(n, mean, var, expected);
        assert!(
            p_value >= alpha,
            "{label} channel {k}: mean {mean} vs expected {expected} (t = {t:.3}, p = {p_value:.3e})"
        );
    }
}

/// Smallest z-test p-value over the `block`-pixel regions and channels of a `res x res` render
/// `a` against `b(bx, by, k)` = (mean, variance of the mean) of the other image's region; with
/// a description of where it was.
pub fn worst_region(
    a: &Framebuffer,
    res: u32,
    block: u32,
    b: impl Fn(u32, u32, usize) -> (f64, f64),
) -> (f64, String) {
    worst_region_rect(a, res, res, block, b)
}

/// [`worst_region`] of a `width x height` render (both multiples of `block`).
pub fn worst_region_rect(
    a: &Framebuffer,
    width: u32,
    height: u32,
    block: u32,
    b: impl Fn(u32, u32, usize) -> (f64, f64),
) -> (f64, String) {
    assert_eq!((a.width, a.height), (width, height), "render size");
    assert!(
        width.is_multiple_of(block) && height.is_multiple_of(block),
        "{width}x{height} is not a whole number of {block}-pixel blocks"
    );
    let mut worst = (1.0, String::new());
    for by in 0..height / block {
        for bx in 0..width / block {
            let sa = region_stats(a, bx * block, by * block, block, block);
            for (k, &(ma, va)) in sa.iter().enumerate() {
                let (mb, vb) = b(bx, by, k);
                let z = (ma - mb) / (va + vb).sqrt();
                let p = z_p_value(z);
                if p < worst.0 {
                    worst = (
                        p,
                        format!("region ({bx},{by}) channel {k}: {ma:.5} vs {mb:.5}, z = {z:.2}"),
                    );
                }
            }
        }
    }
    worst
}

/// A render made the way Mitsuba 3 made its references, lights picked uniformly as its emitter
/// sampling does, on 2 threads: its per-pixel variance stands in for the reference's own in
/// [`worst_against_reference`]. Tessera's default light choice (by contribution at each vertex)
/// has a lower variance than Mitsuba's on scenes with several lights, so our own render's
/// variance, scaled, would understate the reference's noise: on Veach's scene at 2048 spp that
/// made four of eight seeds fail although our two light choices agree with each other at 8192.
pub fn render_like_mitsuba(l: &LoadedScene, spp: u64, seed: u64) -> Framebuffer {
    let mut scene = l.scene.clone();
    scene.set_light_selection(tessera_core::light::LightSelection::Uniform);
    render_two_threads(&scene, &l.integrator, spp, seed)
}

/// Smallest z-test p-value over the `block`-pixel regions of our `res x res` render `ours`
/// against a converged reference image of `ref_spp` samples (Mitsuba 3's, made
/// by scripts/make_refs.sh). The reference's own variance is estimated from `like_ref`, a render
/// of `like_spp` samples made with the reference's estimator ([`render_like_mitsuba`], or `ours`
/// where the two estimators are the same), scaled by the ratio of sample counts, plus a rounding
/// bound: Mitsuba's film sums each 256-spp pass in f32, 256 ulps, which matters only where a
/// region has no noise at all (the bare environment).
#[allow(clippy::too_many_arguments)]
pub fn worst_against_reference(
    ours: &Framebuffer,
    like_ref: &Framebuffer,
    like_spp: u64,
    reference: &tessera::image_io::RgbImage,
    ref_spp: f64,
    res: u32,
    block: u32,
) -> (f64, String) {
    assert_eq!(
        (reference.width, reference.height),
        (res, res),
        "reference size"
    );
    worst_against_reference_rect(ours, like_ref, like_spp, reference, ref_spp, block)
}

/// [`worst_against_reference`] of images of any size (the reference's; both sides multiples of
/// `block`).
pub fn worst_against_reference_rect(
    ours: &Framebuffer,
    like_ref: &Framebuffer,
    like_spp: u64,
    reference: &tessera::image_io::RgbImage,
    ref_spp: f64,
    block: u32,
) -> (f64, String) {
    let (w, h) = (reference.width, reference.height);
    assert_eq!((like_ref.width, like_ref.height), (w, h), "render size");
    worst_region_rect(ours, w, h, block, |bx, by, k| {
        let mut m = 0.0;
        for y in by * block..(by + 1) * block {
            for x in bx * block..(bx + 1) * block {
                m += reference.data[(y * w + x) as usize][k] as f64;
            }
        }
        let m = m / (block * block) as f64;
        let like_var = region_stats(like_ref, bx * block, by * block, block, block)[k].1;
        let rounding = 256.0 * f32::EPSILON as f64 * m.abs();
        (
            m,
            like_var * like_spp as f64 / ref_spp + rounding * rounding,
        )
    })
}

pub mod analytic_scenes;
pub mod bsdf;
pub mod bsdf_checks;
pub mod cap;
pub mod filter_reference;
pub mod phase;
pub mod pixel_ttest;
pub mod rng;
pub mod soup;
pub mod stress;
pub mod wide;

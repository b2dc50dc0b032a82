//! Splatting gives Mitsuba 3's image: the Cornell box at 64x64, rendered by Tessera splatting
//! each sample over the pixels its filter reaches (the default reconstruction), agrees block by
//! block with Mitsuba 3.9.1's references for the Gaussian filter (Mitsuba's default) and the
//! Lanczos filter (negative lobes, 3 pixels of reach): `scenes/refs/cbox_64x64_gaussian_mitsuba.exr`
//! and `cbox_64x64_lanczos_mitsuba.exr`, made by `scripts/make_refs.sh`.
//!
//! Splatted pixels share samples, so a pixel's own sample variance does not give the variance of
//! a block's mean. It is measured instead: `SEEDS` independent renders of `SPP` samples each, a
//! Student t-test of their mean per 4x4 block and channel (`SEEDS - 1` degrees of freedom), the
//! reference's own noise added as the same variance scaled to its sample count. Blocks of 4x4
//! pixels hold enough samples per render for the renders' block means to be close to normal;
//! with 2x2 blocks, dark blocks lit by rare paths made the between-render variance too small a
//! third of the time. Significance 0.01, Šidák-corrected over blocks and channels. Controls:
//! each filter's renders against the other filter's reference must be rejected (they are, at t
//! of 40 and more), so the test tells the filters' shapes apart.
use statrs::distribution::{ContinuousCDF, StudentsT};
use tessera::image_io::read_image;
use tessera::render::{render, RenderOptions};
use tessera_core::render::RenderJob;
use tessera_lab::stats::sidak_alpha;
use tessera_tests::{load_file, scenes_dir};

const RES: u32 = 64;
const BLOCK: u32 = 4;
const SPP: u64 = 32;
const SEEDS: u64 = 32;

/// Per block and channel (row-major blocks, then channel): the mean over the seeds of the
/// block's mean, and the sample variance of the block's mean between seeds.
fn block_stats(rfilter: &str) -> Vec<(f64, f64)> {
    let mut loaded = load_file("cbox.xml", &[("res", "64"), ("rfilter", rfilter)]);
    loaded
        .set_integrator(Some("path_mis"), None)
        .expect("known integrator");
    assert!(loaded.scene.splat.is_some(), "{rfilter} splats");
    let opts = RenderOptions {
        threads: 2,
        tile_size: 16,
        pixels: Default::default(),
    };
    let nb = (RES / BLOCK) as usize;
    let mut per_seed = vec![Vec::new(); nb * nb * 3];
    for seed in 0..SEEDS {
        let job = RenderJob::new(&loaded.scene, &loaded.integrator, 1000 + seed);
        let img = render(&job, 0..SPP, &opts, &mut |_, _| {}).rgb();
        for (b, acc) in per_seed.chunks_mut(3).enumerate() {
            let (bx, by) = ((b % nb) as u32 * BLOCK, (b / nb) as u32 * BLOCK);
            let mut m = [0.0f64; 3];
            for y in by..by + BLOCK {
                for x in bx..bx + BLOCK {
                    for (k, v) in m.iter_mut().enumerate() {
                        *v += img[(y * RES + x) as usize][k] as f64 / (BLOCK * BLOCK) as f64;
                    }
                }
            }
            for k in 0..3 {
                acc[k].push(m[k]);
            }
        }
    }
    per_seed
        .iter()
        .map(|v| {
            let n = v.len() as f64;
            let mean = v.iter().sum::<f64>() / n;
            let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, var)
        })
        .collect()
}

/// The smallest p-value over blocks and channels of `ours` against the reference `name`
/// (`ref_spp` samples per pixel), with where it was.
fn worst_p(ours: &[(f64, f64)], name: &str, ref_spp: f64) -> (f64, String) {
    let reference = read_image(&scenes_dir().join("refs").join(name)).expect("reference image");
    assert_eq!((reference.width, reference.height), (RES, RES));
    let nb = (RES / BLOCK) as usize;
    let t = StudentsT::new(0.0, 1.0, (SEEDS - 1) as f64).expect("dof > 0");
    let mut worst = (1.0, String::new());
    for (i, &(mean, var)) in ours.iter().enumerate() {
        let (b, k) = (i / 3, i % 3);
        let (bx, by) = ((b % nb) as u32 * BLOCK, (b / nb) as u32 * BLOCK);
        let mut r = 0.0;
        for y in by..by + BLOCK {
            for x in bx..bx + BLOCK {
                r += reference.data[(y * RES + x) as usize][k] as f64 / (BLOCK * BLOCK) as f64;
            }
        }
        // The reference's noise: one render's block variance at its sample count; Mitsuba sums
        // in f32, a few ulps where a block has no noise at all.
        let rounding = 256.0 * f32::EPSILON as f64 * r.abs();
        let se = (var / SEEDS as f64 + var * SPP as f64 / ref_spp + rounding * rounding).sqrt();
        let stat = (mean - r) / se;
        let p = 2.0 * t.sf(stat.abs());
        if p < worst.0 {
            worst = (
                p,
                format!(
                    "block ({}, {}) channel {k}: {mean:.5} vs {r:.5}, t = {stat:.2}",
                    bx / BLOCK,
                    by / BLOCK
                ),
            );
        }
    }
    worst
}

fn alpha() -> f64 {
    sidak_alpha(0.01, (RES / BLOCK).pow(2) as usize * 3)
}

const GAUSSIAN_REF: (&str, f64) = ("cbox_64x64_gaussian_mitsuba.exr", 8192.0);
const LANCZOS_REF: (&str, f64) = ("cbox_64x64_lanczos_mitsuba.exr", 8192.0);

#[test]
fn splatting_matches_mitsuba_and_tells_filters_apart() {
    let gaussian = block_stats("gaussian");
    let lanczos = block_stats("lanczos");
    for (label, ours, (name, spp)) in [
        ("gaussian", &gaussian, GAUSSIAN_REF),
        ("lanczos", &lanczos, LANCZOS_REF),
    ] {
        let (p, what) = worst_p(ours, name, spp);
        eprintln!("{label}: Tessera splatting vs Mitsuba 3: worst p = {p:.3e} at {what}");
        assert!(
            p >= alpha(),
            "{label}: p = {p:.3e} < {:.3e} at {what}",
            alpha()
        );
    }
    // Controls: the other filter's image.
    for (label, ours, (name, spp)) in [
        ("gaussian against lanczos", &gaussian, LANCZOS_REF),
        ("lanczos against gaussian", &lanczos, GAUSSIAN_REF),
    ] {
        let (p, what) = worst_p(ours, name, spp);
        eprintln!("control, {label}: worst p = {p:.3e} at {what}");
        assert!(p < alpha(), "{label} passed (p = {p:.3e})");
    }
}

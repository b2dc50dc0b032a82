//! The `aov` and `moment` integrators' extra channels.
//!
//! `aov`: tests/aov/aov.xml (a diffuse sphere on a two-sided diffuse floor under a constant sky,
//! 32x32, box filter; depth, shading normal, position and albedo beside a path tracer) against
//! Mitsuba 3.9.1's render of the same file (tests/aov/aov_ref.exr, 1024 spp, by
//! scripts/mitsuba_aov_ref.py): the channel names and order are Mitsuba's, and every channel
//! agrees region by region (8x8 pixels, pixels as strata) in a z-test whose reference variance
//! is our own per-pixel variance scaled by the sample-count ratio (both renderers average the
//! same variable over uniformly placed box-filter samples), plus a float rounding allowance of
//! 1e-4 relative. Where a region meets no silhouette its variables are smooth, so the test is
//! then as tight as the rounding allowance. Sidak-corrected significance 0.01 over every
//! compared region and channel. Controls that must fail: the normal's X and Z swapped, the
//! albedo 3% darker, the colour 5% darker.
//!
//! `aov` derivatives and indices: tests/aov/aov_index.xml (a sphere, an instance of a rotated
//! rectangle, a disk, a cylinder and two rectangles Mitsuba joins into one mesh, before a wall;
//! `dp_du`, `dp_dv`, `duv_dx`, `duv_dy`, `prim_index`, `shape_index`, `uv`) against Mitsuba
//! 3.9.1's render (tests/aov/aov_index_ref.exr, 1024 spp, scalar_rgb) by the same region test;
//! Mitsuba shortens the camera ray's differentials by `1 / sqrt(spp)`, so our `duv` at 256 spp
//! is compared with twice the reference's. The indices also agree exactly at every pixel where
//! both renders are whole numbers (the pixel saw one primitive of one shape). Controls that must
//! fail: `dp_du` and `dp_dv` swapped, the `duv` scale not applied, the shape order reversed.
//!
//! `moment`: each sample's XYZ square is what the second-moment channel averages: computed here
//! from the nested integrator's per-sample values, it matches the channel to float rounding,
//! and the square of the mean (the control) does not.
//!
//! Determinism: a layer renders the same bits on 1 and 2 threads with different tiles.
use std::ops::Range;
use std::path::{Path, PathBuf};
use tessera::image_io::RgbImage;
use tessera::layers::{gathered_aovs, read_channels_exr, render_layer, render_layers};
use tessera::render::{render_span, Framebuffer, RenderOptions, Span};
use tessera_core::glam::DVec3;
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;
use tessera_lab::stats::sidak_alpha;
use tessera_scene::{load_scene, load_scene_str, LoadedScene};
use tessera_tests::{region_stats, render_loaded, worst_against_reference_rect, z_p_value};

const SPP: u64 = 256;
const REF_SPP: f64 = 1024.0;
const BLOCK: u32 = 8;
const SEED: u64 = 3;

fn scene_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("aov/aov.xml")
}

fn opts(threads: usize, tile_size: u32) -> RenderOptions {
    RenderOptions {
        threads,
        tile_size,
        pixels: Default::default(),
    }
}

/// Mitsuba 3's reference channels, by name.
fn reference() -> Vec<(String, Vec<f32>)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("aov/aov_ref.exr");
    let (w, h, channels) = read_channels_exr(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((w, h), (32, 32));
    channels.into_iter().map(|c| (c.name, c.values)).collect()
}

fn channel<'a>(r: &'a [(String, Vec<f32>)], name: &str) -> &'a [f32] {
    &r.iter()
        .find(|c| c.0 == name)
        .unwrap_or_else(|| panic!("no channel {name} in the reference"))
        .1
}

/// Smallest p-value over the regions of `fb`'s colour channels `ks` against reference planes
/// `refs` (one per channel of `ks`), with where it was.
fn worst(fb: &Framebuffer, ks: &[usize], refs: &[&[f32]]) -> (f64, String) {
    let (w, h) = (fb.width, fb.height);
    let mut worst = (1.0, String::new());
    for by in 0..h / BLOCK {
        for bx in 0..w / BLOCK {
            let ours = region_stats(fb, bx * BLOCK, by * BLOCK, BLOCK, BLOCK);
            for (&k, plane) in ks.iter().zip(refs) {
                let mut m = 0.0;
                for y in by * BLOCK..(by + 1) * BLOCK {
                    for x in bx * BLOCK..(bx + 1) * BLOCK {
                        m += plane[(y * w + x) as usize] as f64;
                    }
                }
                let m = m / (BLOCK * BLOCK) as f64;
                let (mo, vo) = ours[k];
                let rounding = 1e-4 * m.abs().max(mo.abs()) + 1e-6;
                let var = vo + vo * SPP as f64 / REF_SPP + rounding * rounding;
                let z = (mo - m) / var.sqrt();
                let p = z_p_value(z);
                if p < worst.0 {
                    worst = (
                        p,
                        format!("region ({bx},{by}) channel {k}: {mo:.6} vs {m:.6}, z = {z:.2}"),
                    );
                }
            }
        }
    }
    worst
}

/// The channel names, in order, that Mitsuba 3.9.1's film holds for tests/aov/aov.xml.
const MITSUBA_ORDER: &[&str] = &[
    "img.R", "img.G", "img.B", "img.A", "dd.y.T", "nn.X", "nn.Y", "nn.Z", "pos.X", "pos.Y",
    "pos.Z", "alb.R", "alb.G", "alb.B",
];

/// The names of the extra channels `l`'s integrator writes, in order.
fn layer_names(l: &LoadedScene) -> Vec<&str> {
    l.integrator_spec
        .layers
        .iter()
        .flat_map(|layer| layer.names.iter().map(String::as_str))
        .collect()
}

#[test]
fn aov_channels_match_mitsuba() {
    let l = load_scene(&scene_path(), &[]).unwrap_or_else(|e| panic!("{e}"));
    let names = layer_names(&l);
    assert_eq!(names, MITSUBA_ORDER);
    let r = reference();
    let mut in_file: Vec<&str> = r.iter().map(|c| c.0.as_str()).collect();
    in_file.retain(|n| !["R", "G", "B"].contains(n));
    let mut sorted = names.clone();
    sorted.sort();
    assert_eq!(in_file, sorted, "the reference's channels");

    let tests = (32 / BLOCK).pow(2) as usize * (3 + names.len());
    let alpha = sidak_alpha(0.01, tests);
    // The colour: Mitsuba's R, G, B are its first nested integrator's.
    let ours = render_loaded(&l, SPP, SEED);
    let rgb = |scale: f32| RgbImage {
        width: 32,
        height: 32,
        data: (0..32 * 32)
            .map(|i| ["R", "G", "B"].map(|n| channel(&r, n)[i] * scale))
            .collect(),
    };
    let (p, at) = worst_against_reference_rect(&ours, &ours, SPP, &rgb(1.0), REF_SPP, BLOCK);
    assert!(p > alpha, "colour: p = {p:.2e} at {at}");
    let (p, at) = worst_against_reference_rect(&ours, &ours, SPP, &rgb(0.95), REF_SPP, BLOCK);
    assert!(
        p < alpha,
        "control (colour 5% darker) passed: p = {p:.2e} at {at}"
    );

    for layer in &l.integrator_spec.layers {
        let fb = render_layer(&l.scene, layer, SEED, 0..SPP, &opts(2, 16)).unwrap();
        let ks: Vec<usize> = (0..layer.names.len()).collect();
        let refs: Vec<&[f32]> = layer.names.iter().map(|n| channel(&r, n)).collect();
        let (p, at) = worst(&fb, &ks, &refs);
        assert!(p > alpha, "{:?}: p = {p:.2e} at {at}", layer.names);
        eprintln!("{:?}: worst p = {p:.3} at {at}", layer.names);
        if layer.names[0] == "nn.X" {
            let swapped = [refs[2], refs[1], refs[0]];
            let (p, at) = worst(&fb, &ks, &swapped);
            assert!(
                p < alpha,
                "control (nn X and Z swapped) passed: p = {p:.2e} at {at}"
            );
        }
        if layer.names[0] == "alb.R" {
            let darker: Vec<Vec<f32>> = refs
                .iter()
                .map(|c| c.iter().map(|v| v * 0.97).collect())
                .collect();
            let darker: Vec<&[f32]> = darker.iter().map(Vec::as_slice).collect();
            let (p, at) = worst(&fb, &ks, &darker);
            assert!(
                p < alpha,
                "control (albedo 3% darker) passed: p = {p:.2e} at {at}"
            );
        }
    }
}

/// Like [`worst`], skipping regions where the reference is not finite (Mitsuba's `duv` of a
/// ray that meets nothing is NaN) and scaling the reference by `scale`.
fn worst_finite(fb: &Framebuffer, ks: &[usize], refs: &[&[f32]], scale: f32) -> (f64, String) {
    let scaled: Vec<Vec<f32>> = refs
        .iter()
        .map(|c| {
            c.iter()
                .map(|v| if v.is_finite() { v * scale } else { f32::NAN })
                .collect()
        })
        .collect();
    let refs: Vec<&[f32]> = scaled.iter().map(Vec::as_slice).collect();
    let (p, at) = worst(fb, ks, &refs);
    if p.is_nan() {
        return (1.0, at);
    }
    (p, at)
}

/// Pixels where `ours` and `theirs` are both whole numbers, and how many of those differ.
fn whole_pixels(ours: &[f32], theirs: &[f32]) -> (usize, usize) {
    let whole = |v: f32| v.is_finite() && (v - v.round()).abs() < 1e-4;
    let both: Vec<(f32, f32)> = ours
        .iter()
        .zip(theirs)
        .map(|(&a, &b)| (a, b))
        .filter(|&(a, b)| whole(a) && whole(b))
        .collect();
    let differ = both.iter().filter(|(a, b)| a.round() != b.round()).count();
    (both.len(), differ)
}

#[test]
fn aov_derivatives_and_indices_match_mitsuba() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("aov");
    let l = load_scene(&dir.join("aov_index.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let names = layer_names(&l);
    assert_eq!(
        names,
        [
            "du.X", "du.Y", "du.Z", "dv.X", "dv.Y", "dv.Z", "dx.U", "dx.V", "dy.U", "dy.V", "pi.I",
            "si.I", "uv.U", "uv.V"
        ]
    );
    let (w, h, channels) =
        read_channels_exr(&dir.join("aov_index_ref.exr")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((w, h), (32, 32));
    let r: Vec<(String, Vec<f32>)> = channels.into_iter().map(|c| (c.name, c.values)).collect();
    let tests = (32 / BLOCK).pow(2) as usize * names.len();
    let alpha = sidak_alpha(0.01, tests);
    // Mitsuba's differentials are 1/sqrt(spp) long: ours at SPP against its at REF_SPP.
    let duv_scale = (REF_SPP / SPP as f64).sqrt() as f32;
    let mut fbs = Vec::new();
    for layer in &l.integrator_spec.layers {
        let fb = render_layer(&l.scene, layer, SEED, 0..SPP, &opts(2, 16)).unwrap();
        let ks: Vec<usize> = (0..layer.names.len()).collect();
        let refs: Vec<&[f32]> = layer.names.iter().map(|n| channel(&r, n)).collect();
        let duv = layer.names[0].starts_with('d') && layer.names[0].ends_with(".U");
        let scale = if duv { duv_scale } else { 1.0 };
        let (p, at) = worst_finite(&fb, &ks, &refs, scale);
        eprintln!("{:?}: worst p = {p:.3} at {at}", layer.names);
        assert!(p > alpha, "{:?}: p = {p:.2e} at {at}", layer.names);
        if duv {
            let (p, at) = worst_finite(&fb, &ks, &refs, 1.0);
            assert!(
                p < alpha,
                "control ({:?} without the 1/sqrt(spp) scale) passed: p = {p:.2e} at {at}",
                layer.names
            );
        }
        fbs.push((layer.names.clone(), fb));
    }
    // Control: dp_du against Mitsuba's dp_dv.
    let du = &fbs.iter().find(|f| f.0[0] == "du.X").unwrap().1;
    let swapped: Vec<&[f32]> = ["dv.X", "dv.Y", "dv.Z"]
        .iter()
        .map(|n| channel(&r, n))
        .collect();
    let (p, at) = worst_finite(du, &[0, 1, 2], &swapped, 1.0);
    assert!(
        p < alpha,
        "control (dp_du and dp_dv swapped) passed: p = {p:.2e} at {at}"
    );

    // The indices, pixel by pixel.
    let plane = |name: &str| -> Vec<f32> {
        let fb = &fbs.iter().find(|f| f.0[0] == name).unwrap().1;
        (0..32 * 32)
            .map(|i| fb.at(i % 32, i / 32).mean()[0])
            .collect()
    };
    for name in ["pi.I", "si.I"] {
        let (compared, differ) = whole_pixels(&plane(name), channel(&r, name));
        eprintln!("{name}: {compared} whole pixels, {differ} differ");
        assert!(
            compared > 700,
            "{name}: only {compared} pixels saw one primitive"
        );
        assert_eq!(differ, 0, "{name}: {differ} of {compared} pixels differ");
    }
    // Control: the shapes listed in reverse order (5 shapes).
    let reversed: Vec<f32> = plane("si.I")
        .iter()
        .map(|&v| if v > 0.0 { 6.0 - v } else { v })
        .collect();
    let (compared, differ) = whole_pixels(&reversed, channel(&r, "si.I"));
    assert!(
        differ > compared / 10,
        "control (shape order reversed) passed: {differ} of {compared} differ"
    );
}

/// The scene of tests/aov/aov.xml with `moment` over a path tracer and a direct integrator.
fn moment_scene() -> LoadedScene {
    let text = std::fs::read_to_string(scene_path()).unwrap();
    let (a, b) = (
        text.find("<integrator type=\"aov\">").unwrap(),
        text.rfind("</integrator>").unwrap() + "</integrator>".len(),
    );
    let moment = "<integrator type=\"moment\">\n<integrator type=\"path\" name=\"p\">\
                  <integer name=\"max_depth\" value=\"4\"/></integrator>\n\
                  <integrator type=\"direct\" name=\"d\"/>\n</integrator>";
    let text = format!("{}{moment}{}", &text[..a], &text[b..]);
    load_scene_str(&text, &scene_path(), &[]).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn moment_second_moment_is_the_mean_of_squared_samples() {
    let l = moment_scene();
    let names = layer_names(&l);
    assert_eq!(
        names,
        [
            "p.X", "p.Y", "p.Z", "d.X", "d.Y", "d.Z", "m2_p.X", "m2_p.Y", "m2_p.Z", "m2_d.X",
            "m2_d.Y", "m2_d.Z"
        ]
    );
    assert_eq!(
        l.integrator_spec.name, "path",
        "the image is the first nested integrator's"
    );
    let spp = 16;
    let second = &l.integrator_spec.layers[2];
    assert_eq!(second.names[0], "m2_p.X");
    let fb = render_layer(&l.scene, second, SEED, 0..spp, &opts(2, 8)).unwrap();
    let first = render_layer(
        &l.scene,
        &l.integrator_spec.layers[0],
        SEED,
        0..spp,
        &opts(2, 8),
    )
    .unwrap();
    let job = RenderJob::new(&l.scene, &l.integrator, SEED);
    let m = tessera_core::integrator::SRGB_TO_XYZ.as_dmat3();
    let (mut bad, mut control_bad, mut worst) = (0, 0, 0.0f64);
    for y in 0..32 {
        for x in 0..32 {
            let (mut sum, mut sum_sq) = (DVec3::ZERO, DVec3::ZERO);
            for i in 0..spp {
                let xyz = m * job.sample(x, y, i).as_dvec3();
                sum += xyz;
                sum_sq += xyz * xyz;
            }
            let (mean, mean_sq) = (sum / spp as f64, sum_sq / spp as f64);
            let got = DVec3::from(fb.at(x, y).mean().map(f64::from));
            let got_first = DVec3::from(first.at(x, y).mean().map(f64::from));
            for k in 0..3 {
                let tol = 1e-5 * mean_sq[k].abs() + 1e-7;
                let d = (got[k] - mean_sq[k]).abs();
                worst = worst.max(d / tol);
                bad += (d > tol) as u32;
                bad += ((got_first[k] - mean[k]).abs() > 1e-5 * mean[k].abs() + 1e-7) as u32;
                control_bad += ((mean[k] * mean[k] - got[k]).abs() > tol) as u32;
            }
        }
    }
    assert_eq!(bad, 0, "worst difference {worst:.2} tolerances");
    // Control: the square of the mean is not the mean of the squares (most pixels are noisy).
    assert!(
        control_bad > 1500,
        "control passed in {} channels",
        3072 - control_bad
    );
}

#[test]
fn layers_are_the_same_bits_on_any_thread_count() {
    let l = load_scene(&scene_path(), &[]).unwrap_or_else(|e| panic!("{e}"));
    for layer in [&l.integrator_spec.layers[0], &l.integrator_spec.layers[5]] {
        let a = render_layer(&l.scene, layer, SEED, 0..8, &opts(1, 32)).unwrap();
        let b = render_layer(&l.scene, layer, SEED, 0..8, &opts(2, 5)).unwrap();
        assert!(a == b, "{:?} differs between thread counts", layer.names);
        let c = render_layer(&l.scene, layer, SEED + 1, 0..8, &opts(2, 5)).unwrap();
        assert!(
            a != c,
            "control: another seed gives the same {:?}",
            layer.names
        );
    }
}

/// The colour render of `l` at `spp` samples a pixel, gathering its samples' XYZ squares.
fn colour(l: &LoadedScene, spp: u64) -> Framebuffer {
    let job = RenderJob::new(&l.scene, &l.integrator, SEED);
    let mut fb = Framebuffer::for_job(&job).with_squares();
    render_span::<NoProbe>(
        &job,
        &opts(2, 8),
        &mut fb,
        Span::Fixed(0..spp),
        None,
        &mut |_, _| {},
    );
    fb
}

/// A layer whose integrator is the colour's is taken from the colour's samples instead of
/// rendered again: the first nested integrator's colour of `aov` bit for bit, the first moment
/// of `moment` up to rounding (XYZ of the mean against the mean of XYZ). Control: once the
/// command line changes the colour's integrator, the layer is rendered, and differs from the
/// new colour converted.
#[test]
fn layers_of_the_colours_integrator_come_from_the_colour() {
    let spp = 8;
    let l = load_scene(&scene_path(), &[]).unwrap_or_else(|e| panic!("{e}"));
    let first = &l.integrator_spec.layers[..1];
    assert!(first[0].colour, "{:?}", first[0].names);
    let got = render_layers(
        &l.scene,
        first,
        SEED,
        0..spp,
        &opts(2, 8),
        &colour(&l, spp).rgb(),
        None,
    )
    .unwrap();
    let want = render_layer(&l.scene, &first[0], SEED, 0..spp, &opts(1, 16))
        .unwrap()
        .rgb();
    for (c, ch) in got.iter().enumerate() {
        assert!(
            ch.values
                .iter()
                .zip(&want)
                .all(|(a, b)| a.to_bits() == b[c].to_bits()),
            "aov {} differs from its render",
            ch.name
        );
    }

    let mut l = moment_scene();
    let first = l.integrator_spec.layers[..1].to_vec();
    let marked: Vec<bool> = l.integrator_spec.layers.iter().map(|l| l.colour).collect();
    assert_eq!(marked, [true, false, true, false]);
    let derived = |l: &LoadedScene| {
        render_layers(
            &l.scene,
            &first,
            SEED,
            0..spp,
            &opts(2, 8),
            &colour(l, spp).rgb(),
            None,
        )
        .unwrap()
    };
    let rendered = render_layer(&l.scene, &first[0], SEED, 0..spp, &opts(2, 8))
        .unwrap()
        .rgb();
    let close = |chs: &[tessera::layers::Channel]| {
        chs.iter().enumerate().all(|(c, ch)| {
            ch.values
                .iter()
                .zip(&rendered)
                .all(|(a, b)| (a - b[c]).abs() <= 1e-5 * b[c].abs() + 1e-7)
        })
    };
    assert!(
        close(&derived(&l)),
        "first moment from the colour is not the rendered one"
    );
    l.set_integrator(Some("direct"), None).unwrap();
    assert!(!l.integrator_spec.layers[0].colour);
    let first = l.integrator_spec.layers[..1].to_vec();
    let after = render_layers(
        &l.scene,
        &first,
        SEED,
        0..spp,
        &opts(2, 8),
        &colour(&l, spp).rgb(),
        None,
    );
    assert!(
        close(&after.unwrap()),
        "rendered again, the layer is the path tracer's"
    );
    let converted: Vec<_> = colour(&l, spp)
        .rgb()
        .iter()
        .map(|c| {
            (tessera_core::integrator::SRGB_TO_XYZ * tessera_core::glam::Vec3::from(*c)).to_array()
        })
        .collect();
    let differ = converted
        .iter()
        .zip(&rendered)
        .filter(|(a, b)| (0..3).any(|k| (a[k] - b[k]).abs() > 1e-5 * b[k].abs() + 1e-7))
        .count();
    assert!(
        differ > 100,
        "control: the direct colour converted matches the path's moment ({differ})"
    );
}

/// The second moment of the colour's own integrator is gathered by the colour's pass: the same
/// bits as a render of the `moment` integrator's square, on any thread count and tile size, and
/// with the pass split in two. Control: after the command line changes the colour's integrator,
/// the squares the colour's pass gathers are another integrator's and differ from the layer
/// (which is then rendered, and is still the path tracer's).
#[test]
fn second_moment_comes_from_the_colours_pass() {
    let spp = 8;
    let mut l = moment_scene();
    let second = l.integrator_spec.layers[2].clone();
    assert!(second.colour && second.names[0] == "m2_p.X");
    let want = render_layer(&l.scene, &second, SEED, 0..spp, &opts(1, 16)).unwrap();
    let fb = colour(&l, spp);
    let squares = fb.squares.as_deref().expect("squares gathered");
    assert!(
        squares.rgb() == want.rgb(),
        "gathered squares differ from the render"
    );
    let got = render_layers(
        &l.scene,
        std::slice::from_ref(&second),
        SEED,
        0..spp,
        &opts(2, 8),
        &fb.rgb(),
        Some(&fb),
    )
    .unwrap();
    let bits = |chs: &[tessera::layers::Channel], want: &[[f32; 3]]| {
        chs.iter().enumerate().all(|(c, ch)| {
            ch.values
                .iter()
                .zip(want)
                .all(|(a, b)| a.to_bits() == b[c].to_bits())
        })
    };
    assert!(
        bits(&got, &want.rgb()),
        "the layer is not the gathered squares"
    );
    // One thread, other tiles, two spans: the same bits.
    let job = RenderJob::new(&l.scene, &l.integrator, SEED);
    let mut split = Framebuffer::for_job(&job).with_squares();
    for span in [0..3, 3..spp] {
        render_span::<NoProbe>(
            &job,
            &opts(1, 5),
            &mut split,
            Span::Fixed(span),
            None,
            &mut |_, _| {},
        );
    }
    assert!(split == fb, "squares depend on threads, tiles or spans");

    l.set_integrator(Some("direct"), None).unwrap();
    let second = l.integrator_spec.layers[2].clone();
    assert!(!second.colour);
    let fb = colour(&l, spp);
    let got = render_layers(
        &l.scene,
        &[second],
        SEED,
        0..spp,
        &opts(2, 8),
        &fb.rgb(),
        Some(&fb),
    )
    .unwrap();
    assert!(
        bits(&got, &want.rgb()),
        "rendered again, the layer is the path tracer's"
    );
    let gathered = fb.squares.as_deref().unwrap().rgb();
    let differ = gathered
        .iter()
        .zip(want.rgb())
        .filter(|(a, b)| (0..3).any(|k| a[k].to_bits() != b[k].to_bits()))
        .count();
    assert!(
        differ > 100,
        "control: the direct colour's squares match the path's second moment ({differ})"
    );
}

/// The test scene with its box filter replaced by `filter` (and, with `sampled`, the filter
/// importance-sampled: samples of a filter with negative lobes then carry a signed weight).
fn filtered_scene(filter: &str, sampled: bool) -> LoadedScene {
    let text = std::fs::read_to_string(scene_path()).unwrap();
    let text = text.replace(
        "<rfilter type=\"box\"/>",
        &format!("<rfilter type=\"{filter}\"/>"),
    );
    let mut l = load_scene_str(&text, &scene_path(), &[]).unwrap_or_else(|e| panic!("{e}"));
    if sampled {
        l.scene.splat = None;
    }
    l
}

/// The colour render of `l` from `seed` at `spp` samples a pixel, gathering its surface
/// variables, on `o`'s threads and tiles, in the spans `spans`.
fn colour_with_aovs(
    l: &LoadedScene,
    seed: u64,
    spp: u64,
    o: &RenderOptions,
    spans: &[Range<u64>],
) -> Framebuffer {
    let job = RenderJob::new(&l.scene, &l.integrator, seed);
    let aovs = gathered_aovs(&l.integrator_spec.layers, spp);
    let mut fb = Framebuffer::for_job(&job).with_aovs(aovs);
    for span in spans {
        render_span::<NoProbe>(
            &job,
            o,
            &mut fb,
            Span::Fixed(span.clone()),
            None,
            &mut |_, _| {},
        );
    }
    fb
}

/// Surface variables are gathered in the colour's pass: each layer the same bits as a render of
/// its own integrator, with the filter splatted (Gaussian), in its own pixel (box) and
/// importance-sampled with negative lobes (Lanczos: signed sample weights), on any thread count,
/// tile size and split of the pass. Control: gathered from a colour pass with another seed, the
/// layers differ from the renders in many pixels.
#[test]
fn surface_variables_come_from_the_colours_pass() {
    let spp = 8;
    for (filter, sampled) in [("gaussian", false), ("box", false), ("lanczos", true)] {
        let l = filtered_scene(filter, sampled);
        let layers: Vec<_> = l
            .integrator_spec
            .layers
            .iter()
            .filter(|x| matches!(x.source, tessera_scene::LayerSource::Aov(_)))
            .cloned()
            .collect();
        // depth, normal, position, albedo, and the nested path tracer's alpha.
        assert_eq!(layers.len(), 5, "{filter}");
        let want: Vec<f32> = layers
            .iter()
            .flat_map(|x| {
                let fb = render_layer(&l.scene, x, SEED, 0..spp, &opts(1, 16)).unwrap();
                let rgb = fb.rgb();
                (0..x.names.len())
                    .flat_map(move |c| rgb.iter().map(move |p| p[c]).collect::<Vec<_>>())
            })
            .collect();
        let gathered = |fb: &Framebuffer| -> Vec<f32> {
            render_layers(
                &l.scene,
                &layers,
                SEED,
                0..spp,
                &opts(2, 8),
                &fb.rgb(),
                Some(fb),
            )
            .unwrap()
            .into_iter()
            .flat_map(|c| c.values)
            .collect()
        };
        let fb = colour_with_aovs(&l, SEED, spp, &opts(2, 8), std::slice::from_ref(&(0..spp)));
        assert_eq!(fb.aovs.len(), 5);
        let got = gathered(&fb);
        assert_eq!(got.len(), want.len());
        assert!(
            got.iter()
                .zip(&want)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "{filter}: gathered variables differ from their renders"
        );
        let other = colour_with_aovs(&l, SEED, spp, &opts(1, 5), &[0..3, 3..spp]);
        assert!(
            other == fb,
            "{filter}: gathering depends on threads, tiles or spans"
        );

        let control = gathered(&colour_with_aovs(
            &l,
            SEED + 1,
            spp,
            &opts(2, 8),
            std::slice::from_ref(&(0..spp)),
        ));
        let differ = control
            .iter()
            .zip(&want)
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert!(
            differ > 200,
            "{filter}: control: another seed's variables match ({differ})"
        );
    }
}

//! `tessera bench --fresh`: each wave's image is a render from scratch with the sampler set up
//! for that wave's sample count, bit for bit what `render --spp N` makes (and, for zsobol, not
//! the continuing waves' image); adaptive fresh waves are the continuing schedule run from
//! scratch with zsobol set up as `render --adaptive` sets it up, bit for bit that command's
//! image; the command line names the curves `SAMPLER+fresh`. Nothing here depends on timing.

use std::path::{Path, PathBuf};
use std::process::Command;
use tessera::image_io::{read_image, write_image, RgbImage};
use tessera::render::{render, Framebuffer, RenderOptions};
use tessera_core::adaptive::{AdaptiveParams, ZSOBOL_BLOCK_FACTOR};
use tessera_core::render::RenderJob;
use tessera_lab::bench::fresh::run_fresh;
use tessera_lab::bench::{errors, read_csv, run_waves, Row, WaveLimits};
use tessera_scene::{load_scene, LoadedScene};

const BIN: &str = env!("CARGO_BIN_EXE_tessera");

fn cbox() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml")
}

/// The 12x12 box-filtered Cornell box with `sampler`.
fn small_cbox(sampler: &str) -> LoadedScene {
    let d: Vec<(String, String)> = [("res", "12"), ("rfilter", "box")]
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    let mut l = load_scene(&cbox(), &d).expect("cbox loads");
    l.set_sampler(Some(sampler), 1 << 20).unwrap();
    l
}

fn opts() -> RenderOptions {
    RenderOptions {
        threads: 2,
        tile_size: 5,
        pixels: Default::default(),
    }
}

/// Samples `samples` of `l` with seed 3.
fn plain_render(l: &LoadedScene, samples: std::ops::Range<u64>) -> Framebuffer {
    let job = RenderJob::new(&l.scene, &l.integrator, 3);
    render(&job, samples, &opts(), &mut |_, _| {})
}

fn flat_reference(l: &LoadedScene) -> RgbImage {
    let (w, h) = (l.scene.camera.width, l.scene.camera.height);
    RgbImage {
        width: w,
        height: h,
        data: vec![[0.2, 0.1, 0.05]; (w * h) as usize],
    }
}

/// An empty folder of this process for test `name`'s files.
fn empty_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tessera-fresh-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const LIMITS: WaveLimits = WaveLimits {
    max_seconds: 1e9,
    max_spp: 8,
};

/// The continuing waves' rows of `l` up to `limits.max_spp` (with the sampler as `l` has it).
fn continuing(
    l: &LoadedScene,
    reference: &RgbImage,
    limits: WaveLimits,
    adaptive: Option<&AdaptiveParams>,
) -> Vec<Row> {
    let job = RenderJob::new(&l.scene, &l.integrator, 3);
    let (rows, _) = run_waves(
        &job,
        "path",
        &opts(),
        reference,
        limits,
        adaptive,
        &mut |_| {},
    );
    rows
}

/// The fresh rows of `l` (sampler restored afterwards, as the function promises).
fn fresh(l: &mut LoadedScene, adaptive: Option<&AdaptiveParams>) -> Vec<Row> {
    let before = l.scene.sampler;
    let reference = flat_reference(l);
    let mut seen = 0;
    let rows = run_fresh(
        &mut l.scene,
        &l.integrator,
        3,
        "path",
        &opts(),
        &reference,
        LIMITS,
        adaptive,
        &mut |_| seen += 1,
    );
    assert_eq!(l.scene.sampler, before, "the scene's sampler is restored");
    assert_eq!(seen, rows.len());
    assert_eq!(rows.iter().map(|r| r.spp).collect::<Vec<_>>(), [1, 2, 4, 8]);
    rows
}

#[test]
fn fresh_waves_are_plain_renders_set_up_for_their_count() {
    let mut l = small_cbox("zsobol");
    let reference = flat_reference(&l);
    let rows = fresh(&mut l, None);
    let base = l.scene.sampler;
    for (r, c) in rows.iter().zip(&continuing(&l, &reference, LIMITS, None)) {
        assert_eq!(r.sampler, "zsobol+fresh");
        l.scene.sampler = base.for_spp(r.spp);
        let plain = plain_render(&l, 0..r.spp);
        assert_eq!(
            r.errors,
            errors(&plain.rgb(), &reference.data),
            "{} spp",
            r.spp
        );
        // The continuing waves use the first samples of a 2^20 block, another image.
        assert_ne!(r.errors, c.errors, "{} spp", r.spp);
    }
}

#[test]
fn fresh_and_continuing_agree_where_the_sampler_ignores_the_count() {
    // The independent sampler draws the same samples whatever the count it is set up for.
    let mut l = small_cbox("independent");
    let reference = flat_reference(&l);
    let rows = fresh(&mut l, None);
    for (r, c) in rows.iter().zip(&continuing(&l, &reference, LIMITS, None)) {
        assert_eq!(r.sampler, "independent+fresh");
        assert_eq!(r.errors, c.errors, "{} spp", r.spp);
    }
}

#[test]
fn adaptive_fresh_waves_run_the_schedule_from_scratch() {
    let mut l = small_cbox("zsobol");
    let reference = flat_reference(&l);
    let params = AdaptiveParams::default();
    let rows = fresh(&mut l, Some(&params));
    let base = l.scene.sampler;
    let schedule = |l: &mut LoadedScene, spp: u64, block: u64| {
        l.scene.sampler = base.for_spp(block);
        let to = WaveLimits {
            max_seconds: 1e9,
            max_spp: spp,
        };
        continuing(l, &reference, to, Some(&params))
            .last()
            .unwrap()
            .errors
    };
    for r in &rows {
        assert_eq!(r.sampler, "zsobol+adaptive+fresh");
        // zsobol's blocks are ZSOBOL_BLOCK_FACTOR times the wave's count, as in render --adaptive.
        let want = schedule(&mut l, r.spp, r.spp * ZSOBOL_BLOCK_FACTOR);
        assert_eq!(r.errors, want, "{} spp", r.spp);
        // Control: blocks of the count itself give another image.
        assert_ne!(r.errors, schedule(&mut l, r.spp, r.spp), "{} spp", r.spp);
    }
    // Past the warm-up the schedule adapts: the 8 spp image is not the uniform one.
    l.scene.sampler = base.for_spp(8 * ZSOBOL_BLOCK_FACTOR);
    let plain = plain_render(&l, 0..8);
    assert_ne!(rows[3].errors, errors(&plain.rgb(), &reference.data));
}

#[test]
fn adaptive_fresh_wave_is_what_render_adaptive_writes() {
    let dir = empty_dir("render");
    let mut l = small_cbox("zsobol");
    let reference = flat_reference(&l);
    let rows = fresh(&mut l, Some(&AdaptiveParams::default()));
    for r in &rows[1..] {
        let out = dir.join(format!("{}.exr", r.spp));
        let o = Command::new(BIN)
            .arg("render")
            .arg(cbox())
            .args(["-D", "res=12", "-D", "rfilter=box", "-D"])
            .arg(format!("spp={}", r.spp))
            .args([
                "--sampler",
                "zsobol",
                "--adaptive",
                "--seed",
                "3",
                "-q",
                "-o",
            ])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{o:?}");
        let image = read_image(&out).unwrap();
        assert_eq!(
            r.errors,
            errors(&image.data, &reference.data),
            "{} spp",
            r.spp
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cli_names_the_fresh_curves() {
    let dir = empty_dir("cli");
    let l = small_cbox("independent");
    let reference = dir.join("ref.exr");
    write_image(&reference, &flat_reference(&l)).unwrap();
    let csv = dir.join("r.csv");
    let o = Command::new(BIN)
        .arg("bench")
        .arg(cbox())
        .args(["-D", "res=12", "-D", "rfilter=box", "--reference"])
        .arg(&reference)
        .args(["--sampler", "zsobol", "--max-spp", "4", "--seed", "3"])
        .args(["--threads", "2", "--adaptive", "--fresh", "-q", "-o"])
        .arg(&csv)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("path (zsobol+fresh) (2 threads): time to relMSE"),
        "{stdout}"
    );
    let got: Vec<(String, u64)> = read_csv(&csv)
        .unwrap()
        .into_iter()
        .map(|r| (r.sampler, r.spp))
        .collect();
    let want: Vec<(String, u64)> = ["zsobol+fresh", "zsobol+adaptive+fresh"]
        .iter()
        .flat_map(|s| [1, 2, 4].map(|n| (s.to_string(), n)))
        .collect();
    assert_eq!(got, want);
    let _ = std::fs::remove_dir_all(&dir);
}

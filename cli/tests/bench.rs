//! `tessera bench`: waves continue one deterministic sample sequence (the framebuffer after the
//! waves of 1, 1 and 2 new samples is bit for bit a plain 4 spp render), the CSV has the
//! documented columns and the errors of exactly those images, `--plot-only` draws a PNG, and bad
//! references are one-line errors with exit code 2 that leave no report behind. Nothing here
//! depends on timing.

use std::path::{Path, PathBuf};
use std::process::Output;
use tessera::image_io::{read_image, write_image, RgbImage};
use tessera::render::{render, render_span, Framebuffer, RenderOptions, Span};
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;
use tessera_lab::bench::{errors, read_csv, run_waves, WaveLimits, CSV_HEADER};
use tessera_scene::{load_scene, LoadedScene};

use crate::support;
use support::run_os;
use support::temp_dir::TempDir;

fn cbox() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml")
}

fn defines() -> Vec<(String, String)> {
    [("res", "12"), ("rfilter", "box")]
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

fn small_cbox() -> LoadedScene {
    load_scene(&cbox(), &defines()).expect("cbox loads")
}

fn opts(threads: usize) -> RenderOptions {
    RenderOptions {
        threads,
        tile_size: 5,
        pixels: Default::default(),
    }
}

/// Samples `samples` of `l` with `seed` on `threads` threads (tiles of 5 pixels).
fn render_seeded(
    l: &LoadedScene,
    samples: std::ops::Range<u64>,
    threads: usize,
    seed: u64,
) -> Framebuffer {
    let job = RenderJob::new(&l.scene, &l.integrator, seed);
    render(&job, samples, &opts(threads), &mut |_, _| {})
}

/// A fresh directory (`tessera-bench-...`), removed on drop.
fn temp_dir(name: &str) -> TempDir {
    TempDir::new("tessera-bench", name)
}

fn os(s: &str) -> &std::ffi::OsStr {
    std::ffi::OsStr::new(s)
}

/// `tessera bench` arguments for the 12x12 box-filtered box `scene` against `reference`.
fn small_args<'a>(scene: &'a Path, reference: &'a Path) -> Vec<&'a std::ffi::OsStr> {
    vec![
        os("bench"),
        scene.as_os_str(),
        os("-D"),
        os("res=12"),
        os("-D"),
        os("rfilter=box"),
        os("--reference"),
        reference.as_os_str(),
    ]
}

/// `tessera bench --waves` on the 12x12 box-filtered box against `reference`, then `rest`.
fn bench_small(reference: &Path, rest: &[&std::ffi::OsStr]) -> Output {
    let scene = cbox();
    let mut args = small_args(&scene, reference);
    args.push(os("--waves"));
    args.extend_from_slice(rest);
    run_os(&args)
}

/// A reference of the small box: its own 16 spp render with another seed.
fn write_reference(dir: &Path, l: &LoadedScene) -> PathBuf {
    let fb = render_seeded(l, 0..16, 2, 99);
    let p = dir.join("ref.exr");
    let img = RgbImage {
        width: fb.width,
        height: fb.height,
        data: fb.rgb(),
    };
    write_image(&p, &img).unwrap();
    p
}

#[test]
fn waves_continue_the_sample_sequence_bit_for_bit() {
    let l = small_cbox();
    let whole = render_seeded(&l, 0..4, 1, 3);
    let mut fb = Framebuffer::new(whole.width, whole.height);
    let job = RenderJob::new(&l.scene, &l.integrator, 3);
    for (range, threads) in [(0..1, 2), (1..2, 1), (2..4, 3)] {
        let span = Span::Fixed(range);
        render_span::<NoProbe>(&job, &opts(threads), &mut fb, span, None, &mut |_, _| {});
    }
    assert_eq!(
        fb, whole,
        "waves 0..1, 1..2, 2..4 differ from one 0..4 render"
    );

    // run_waves stops at --max-spp and ends on the same framebuffer; each row's errors are those
    // of the plain render with that spp.
    let reference = RgbImage {
        width: whole.width,
        height: whole.height,
        data: vec![[0.2, 0.1, 0.05]; (whole.width * whole.height) as usize],
    };
    let limits = WaveLimits {
        max_seconds: 1e9,
        max_spp: 4,
    };
    let mut seen = 0;
    let job = RenderJob::new(&l.scene, &l.integrator, 3);
    let (rows, last) = run_waves(
        &job,
        "path",
        &opts(2),
        &reference,
        limits,
        None,
        &mut |_| seen += 1,
    );
    assert_eq!(last, whole);
    assert_eq!(seen, 3);
    assert_eq!(rows.iter().map(|r| r.spp).collect::<Vec<_>>(), [1, 2, 4]);
    for r in &rows {
        let plain = render_seeded(&l, 0..r.spp, 2, 3);
        assert_eq!(
            r.errors,
            errors(&plain.rgb(), &reference.data),
            "{} spp",
            r.spp
        );
        assert_eq!((r.sampler.as_str(), r.threads), ("independent", 2));
        assert!(r.seconds >= 0.0 && r.errors.relmse > 0.0);
    }
}

#[test]
fn relmse_rmse_mae_of_a_known_image_pair() {
    // Channel differences 0.1 (reference 0), 0.2 (reference 1), 0 (reference 0.5), twice.
    let img = [[0.1, 1.2, 0.5], [0.1, 1.2, 0.5]];
    let reference = [[0.0, 1.0, 0.5], [0.0, 1.0, 0.5]];
    let e = errors(&img, &reference);
    let want_rel = (0.01 / 0.01 + 0.04 / 1.01 + 0.0) / 3.0;
    assert!((e.relmse - want_rel).abs() < 1e-6, "{e:?}");
    assert!((e.rmse - (0.05f64 / 3.0).sqrt()).abs() < 1e-6, "{e:?}");
    assert!((e.mae - 0.1).abs() < 1e-6, "{e:?}");
}

#[test]
fn cli_writes_the_report_and_plots() {
    let tmp = temp_dir("cli");
    let l = small_cbox();
    let reference = write_reference(&tmp.0, &l);
    let (csv, png) = (tmp.0.join("r.csv"), tmp.0.join("r.png"));
    let o = bench_small(
        &reference,
        &[
            os("--integrators"),
            os("path_mis,path_mats"),
            os("--max-spp"),
            os("4"),
            os("--seed"),
            os("3"),
            os("--threads"),
            os("2"),
            os("-q"),
            os("-o"),
            csv.as_os_str(),
            os("--plot"),
            png.as_os_str(),
        ],
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert!(
        stdout.contains("path_mis (2 threads): time to relMSE 0.01"),
        "{stdout}"
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(text.lines().next(), Some(CSV_HEADER));
    assert_eq!(
        CSV_HEADER,
        "integrator,sampler,spp,threads,seconds,samples_per_second,rmse,relmse,mae"
    );
    let rows = read_csv(&csv).unwrap();
    let got: Vec<(&str, u64)> = rows
        .iter()
        .map(|r| (r.integrator.as_str(), r.spp))
        .collect();
    assert_eq!(
        got,
        [
            ("path_mis", 1),
            ("path_mis", 2),
            ("path_mis", 4),
            ("path_mats", 1),
            ("path_mats", 2),
            ("path_mats", 4)
        ]
    );
    // The last path_mis row measures exactly the 4 spp image (the CSV keeps every bit of f64).
    let refimg = read_image(&reference).unwrap();
    let plain = render_seeded(&l, 0..4, 1, 3);
    assert_eq!(rows[2].errors, errors(&plain.rgb(), &refimg.data));
    let plot = image::open(&png).expect("the plot is a PNG");
    assert_eq!((plot.width(), plot.height()), (800, 560));

    // --plot-only draws an existing (e.g. combined) report.
    let png2 = tmp.0.join("only.png");
    let o = run_os(&[
        os("bench"),
        os("--plot-only"),
        csv.as_os_str(),
        os("--plot"),
        png2.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert!(image::open(&png2).is_ok());
}

/// Exit 2, one line on stderr containing `want`, and no report or plot written.
fn assert_bad_input(tmp: &TempDir, o: &Output, want: &str, before: &[String]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(want), "want {want:?} in {err:?}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(tmp.entries(), before, "files were left behind");
}

#[test]
fn bad_references_and_reports_are_one_line_errors() {
    let tmp = temp_dir("bad");
    let l = small_cbox();
    let reference = write_reference(&tmp.0, &l);
    let garbage = tmp.0.join("garbage.exr");
    std::fs::write(&garbage, b"not an exr").unwrap();
    let not_csv = tmp.0.join("not.csv");
    std::fs::write(&not_csv, "a,b\n1,2\n").unwrap();
    let before = tmp.entries();
    let csv = tmp.0.join("r.csv");
    let bench = |reference: &Path, res: &str| {
        run_os(&[
            os("bench"),
            cbox().as_os_str(),
            os("-D"),
            os(res),
            os("--reference"),
            reference.as_os_str(),
            os("--max-spp"),
            os("1"),
            os("-o"),
            csv.as_os_str(),
            os("--plot"),
            tmp.0.join("r.png").as_os_str(),
        ])
    };
    let o = bench(&reference, "res=13");
    assert_bad_input(
        &tmp,
        &o,
        "the reference is 12x12 but the scene renders 13x13",
        &before,
    );
    let o = bench(&garbage, "res=12");
    assert_bad_input(&tmp, &o, "garbage.exr: cannot read image", &before);
    let o = bench(&tmp.0.join("missing.exr"), "res=12");
    assert_bad_input(&tmp, &o, "missing.exr: cannot read image", &before);
    let o = run_os(&[
        os("bench"),
        os("--plot-only"),
        not_csv.as_os_str(),
        os("--plot"),
        tmp.0.join("p.png").as_os_str(),
    ]);
    assert_bad_input(&tmp, &o, "not.csv:1: not a bench report", &before);
    let o = run_os(&[os("bench"), cbox().as_os_str(), os("-o"), csv.as_os_str()]);
    assert_bad_input(&tmp, &o, "--reference", &before);
}

/// `--seeds 2 --seed 3` reports, wave by wave, the mean of the errors of the seed 3 and seed 4
/// images (exactly those renders: the errors are recomputed here); `--seeds 0` is a usage error.
#[test]
fn seeds_average_the_errors_of_each_seeds_images() {
    let tmp = temp_dir("seeds");
    let l = small_cbox();
    let reference = write_reference(&tmp.0, &l);
    let csv = tmp.0.join("r.csv");
    let bench = |seeds: &str| {
        bench_small(
            &reference,
            &[
                os("--integrators"),
                os("path_mis"),
                os("--max-spp"),
                os("2"),
                os("--seed"),
                os("3"),
                os("--seeds"),
                os(seeds),
                os("-q"),
                os("-o"),
                csv.as_os_str(),
            ],
        )
    };
    let o = bench("2");
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let rows = read_csv(&csv).unwrap();
    assert_eq!(rows.iter().map(|r| r.spp).collect::<Vec<_>>(), [1, 2]);
    let refimg = read_image(&reference).unwrap();
    for r in &rows {
        let e: Vec<_> = [3u64, 4]
            .iter()
            .map(|&seed| {
                let img = render_seeded(&l, 0..r.spp, 1, seed);
                errors(&img.rgb(), &refimg.data)
            })
            .collect();
        assert_ne!(e[0].relmse, e[1].relmse, "the seeds must differ");
        let mean = (e[0].relmse + e[1].relmse) / 2.0;
        assert!(
            (r.errors.relmse - mean).abs() <= 1e-12 * mean,
            "{r:?} {e:?}"
        );
        let rmse = ((e[0].rmse.powi(2) + e[1].rmse.powi(2)) / 2.0).sqrt();
        assert!((r.errors.rmse - rmse).abs() <= 1e-12 * rmse, "{r:?} {e:?}");
    }
    std::fs::remove_file(&csv).unwrap();
    let before = tmp.entries();
    let o = bench("0");
    assert_bad_input(&tmp, &o, "--seeds must be at least 1", &before);
}

/// `--repeats 3` renders each curve three times and reports the same images (so the same errors,
/// bit for bit, as one run) with each wave's least time; `--repeats 0` is a usage error.
#[test]
fn repeats_keep_the_images_and_the_least_times() {
    let tmp = temp_dir("repeats");
    let l = small_cbox();
    let reference = write_reference(&tmp.0, &l);
    let csv = tmp.0.join("r.csv");
    let bench = |repeats: &str| {
        let o = bench_small(
            &reference,
            &[
                os("--integrators"),
                os("path_mis"),
                os("--sampler"),
                os("zsobol"),
                os("--max-spp"),
                os("4"),
                os("--repeats"),
                os(repeats),
                os("-o"),
                csv.as_os_str(),
            ],
        );
        let rows = if o.status.code() == Some(0) {
            read_csv(&csv).unwrap()
        } else {
            Vec::new()
        };
        (o, rows)
    };
    let (o, once) = bench("1");
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let (o, thrice) = bench("3");
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    // Three runs of every wave were made (one line each on stderr).
    let err = String::from_utf8_lossy(&o.stderr);
    for run in 1..=3 {
        assert_eq!(
            err.matches(&format!("run {run}):")).count(),
            3,
            "three waves per run: {err}"
        );
    }
    assert_eq!(thrice.iter().map(|r| r.spp).collect::<Vec<_>>(), [1, 2, 4]);
    for (a, b) in once.iter().zip(&thrice) {
        assert_eq!(a.errors, b.errors, "the same images");
        assert!(b.seconds > 0.0 && b.seconds.is_finite());
        let rate = b.spp as f64 * 144.0 / b.seconds;
        assert!((b.samples_per_second - rate).abs() <= 1e-9 * rate, "{b:?}");
    }
    std::fs::remove_file(&csv).unwrap();
    let before = tmp.entries();
    let (o, _) = bench("0");
    assert_bad_input(&tmp, &o, "--repeats must be at least 1", &before);
}

/// `--target-relmse` takes a list and `--ratio-to` prints each curve's time as a ratio to the
/// named curve's (exact between waves, a bound where the peer stops short); a name that fits no
/// curve, or several, is a one-line usage error that writes no plot.
#[test]
fn ratio_to_prints_ratios_and_bounds_for_each_target() {
    let tmp = temp_dir("ratio");
    let csv = tmp.0.join("r.csv");
    // Tessera: relMSE 0.02 at 1 s, 0.005 at 4 s (0.01 at 2 s), 0.0005 at 16 s (0.001 at
    // 4 * 4^(ln 5 / ln 10) = 10.54 s). The peer: 0.02 at 2 s, 0.005 at 8 s (0.01 at 4 s), and it stops there.
    let report = format!(
        "{CSV_HEADER}\n\
         path_mis,zsobol,1,2,1,1,0,0.02,0\n\
         path_mis,zsobol,4,2,4,1,0,0.005,0\n\
         path_mis,zsobol,16,2,16,1,0,0.0005,0\n\
         mitsuba-llvm_ad_rgb:path,independent,1,2,2,1,0,0.02,0\n\
         mitsuba-llvm_ad_rgb:path,independent,4,2,8,1,0,0.005,0\n"
    );
    std::fs::write(&csv, report).unwrap();
    let png = tmp.0.join("p.png");
    let plot_only = |extra: &[&str]| {
        let mut a = vec![
            os("bench"),
            os("--plot-only"),
            csv.as_os_str(),
            os("--plot"),
            png.as_os_str(),
        ];
        a.extend(extra.iter().map(|s| os(s)));
        run_os(&a)
    };
    let o = plot_only(&[
        "--target-relmse",
        "0.01,0.001,0.0001",
        "--ratio-to",
        "mitsuba",
    ]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let out = String::from_utf8_lossy(&o.stdout);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines,
        [
            "path_mis (zsobol) (2 threads): time to relMSE 0.01: 2.000 s (0.50x mitsuba)",
            "mitsuba-llvm_ad_rgb:path (2 threads): time to relMSE 0.01: 4.000 s",
            // The peer needs more than its last 8 s: at most 10.54 / 8.
            "path_mis (zsobol) (2 threads): time to relMSE 0.001: 10.541 s (<= 1.32x mitsuba)",
            "mitsuba-llvm_ad_rgb:path (2 threads): time to relMSE 0.001: not reached \
             (best relMSE 5.000e-3 at 8.000 s)",
            // Neither reaches 1e-4: no bound either way.
            "path_mis (zsobol) (2 threads): time to relMSE 0.0001: not reached \
             (best relMSE 5.000e-4 at 16.000 s) (ratio to mitsuba unknown)",
            "mitsuba-llvm_ad_rgb:path (2 threads): time to relMSE 0.0001: not reached \
             (best relMSE 5.000e-3 at 8.000 s)",
        ],
        "{out}"
    );
    assert!(png.exists());
    std::fs::remove_file(&png).unwrap();
    let before = tmp.entries();
    let o = plot_only(&["--ratio-to", "Mitsuba"]);
    assert_bad_input(&tmp, &o, "--ratio-to Mitsuba: no such curve", &before);
    let o = plot_only(&["--ratio-to", ""]);
    assert_bad_input(&tmp, &o, "names several curves", &before);
    let o = plot_only(&["--target-relmse", "0.01,0"]);
    assert_bad_input(
        &tmp,
        &o,
        "--target-relmse must be positive, found 0",
        &before,
    );
}

/// The default protocol: whole renders from --min-spp, each count's image exactly a plain
/// render of that count (the sampler set up for it), the sample count jumping toward
/// --min-seconds and stopping at --max-spp, the last count rendered twice and kept once; its
/// efficiency printed. Waves-only options without --waves are a usage error.
#[test]
fn the_protocol_renders_whole_images_until_long_enough() {
    let tmp = temp_dir("protocol");
    let l = small_cbox();
    let reference = write_reference(&tmp.0, &l);
    let csv = tmp.0.join("p.csv");
    let scene = cbox();
    let run = |extra: &[&str]| {
        let mut a = small_args(&scene, &reference);
        a.extend([os("--seed"), os("3"), os("-o"), csv.as_os_str()]);
        a.extend(extra.iter().map(|s| os(s)));
        run_os(&a)
    };
    // Never long enough: 4 spp, then straight to the cap of 16, rendered twice.
    let o = run(&["--min-spp", "4", "--min-seconds", "1e9", "--max-spp", "16"]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("16 spp in"), "{stdout}");
    assert!(stdout.contains("efficiency (relMSE x seconds)"), "{stdout}");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(stderr.matches("16 spp").count(), 2, "{stderr}");
    let rows = read_csv(&csv).unwrap();
    assert_eq!(rows.iter().map(|r| r.spp).collect::<Vec<_>>(), [4, 16]);
    let img = read_image(&reference).unwrap();
    for r in &rows {
        let mut fresh = small_cbox();
        fresh.set_sampler(None, r.spp).unwrap();
        let plain = render_seeded(&fresh, 0..r.spp, 2, 3);
        assert_eq!(r.errors, errors(&plain.rgb(), &img.data), "{} spp", r.spp);
    }
    // Long enough at once: one count.
    let o = run(&["--min-spp", "8", "--min-seconds", "0"]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let rows = read_csv(&csv).unwrap();
    assert_eq!(rows.iter().map(|r| r.spp).collect::<Vec<_>>(), [8]);
    // Waves-only options.
    for bad in [&["--adaptive"][..], &["--seeds", "2"], &["--repeats", "2"]] {
        let o = run(bad);
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("add --waves or --fresh"));
    }
}

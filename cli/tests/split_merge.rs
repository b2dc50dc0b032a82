//! Splitting a render and merging the parts, through the `tessera` binary: crop windows and tile
//! sets merge into exactly the bits of one whole render; sample ranges merge into one render of
//! all the samples within float rounding; parts that do not belong together are refused with a
//! one-line error and exit code 2, and so are malformed part files.
use std::path::{Path, PathBuf};
use std::process::Command;
use tessera::image_io::read_image;

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tessera-split-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `tessera ARGS`; returns (exit code, stderr).
fn tessera(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_tessera"))
        .args(args)
        .output()
        .expect("run tessera");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn ok(args: &[&str]) {
    let (code, err) = tessera(args);
    assert_eq!(code, 0, "tessera {args:?} failed: {err}");
}

/// Renders the small Cornell box with extra arguments to `out`.
fn render(out: &Path, extra: &[&str]) {
    let s = scene();
    let mut args = vec![
        "render",
        s.to_str().unwrap(),
        "-D",
        "res=40",
        "-D",
        "spp=4",
        "-q",
        "--tile-size",
        "8",
        "--threads",
        "2",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    ok(&args);
}

fn merge(parts: &[PathBuf], out: &Path, extra: &[&str]) -> (i32, String) {
    let mut args = vec!["merge".to_string()];
    args.extend(parts.iter().map(|p| p.to_str().unwrap().to_string()));
    args.extend(["-o".to_string(), out.to_str().unwrap().to_string()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    tessera(&args)
}

/// Decoded pixels as bits.
fn bits(path: &Path) -> (u32, u32, Vec<u32>) {
    let img = read_image(path).unwrap_or_else(|e| panic!("{e}"));
    let b = img.data.iter().flatten().map(|v| v.to_bits()).collect();
    (img.width, img.height, b)
}

fn assert_refused(code: i32, err: &str, needle: &str) {
    assert_eq!(code, 2, "expected exit 2, got {code}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err}");
    assert!(err.contains(needle), "expected \"{needle}\" in: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn tiles_and_crops_merge_to_the_whole_render_bit_for_bit() {
    let d = dir("spatial");
    let full = d.join("full.exr");
    render(&full, &[]);
    let (w, h, want) = bits(&full);
    assert_eq!((w, h), (40, 40));
    assert!(want.iter().any(|&b| f32::from_bits(b) > 0.0), "black image");

    // Three tile sets.
    let parts: Vec<PathBuf> = (1..=3).map(|k| d.join(format!("t{k}.exr"))).collect();
    for (k, p) in (1..=3).zip(&parts) {
        render(p, &["--tiles", &format!("{k}/3")]);
    }
    let merged = d.join("tiles.exr");
    let (code, err) = merge(&parts, &merged, &["-q"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(bits(&merged), (w, h, want.clone()), "tile sets");

    // Four crop windows that do not follow tile edges, listed out of order, with different
    // thread counts.
    let crops = ["0,0,13,27", "13,0,40,27", "0,27,29,40", "29,27,40,40"];
    let cparts: Vec<PathBuf> = (0..4).map(|i| d.join(format!("c{i}.exr"))).collect();
    for (c, p) in crops.iter().zip(&cparts) {
        render(p, &["--crop", c]);
    }
    let merged = d.join("crops.pfm");
    let mut shuffled = cparts.clone();
    shuffled.reverse();
    let (code, err) = merge(&shuffled, &merged, &["-q"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(bits(&merged), (w, h, want.clone()), "crops");

    // A PNG of a crop is just the window.
    let png = d.join("c0.png");
    render(&png, &["--crop", crops[0]]);
    let (pw, ph, _) = bits(&png);
    assert_eq!((pw, ph), (13, 27));

    // Control: one set missing is refused; allowed, it leaves pixels black and differs.
    let (code, err) = merge(&parts[..2], &d.join("x.exr"), &[]);
    assert_refused(code, &err, "pixels are in no part");
    let partial = d.join("partial.exr");
    let (code, err) = merge(&parts[..2], &partial, &["--allow-missing", "-q"]);
    assert_eq!(code, 0, "{err}");
    assert_ne!(
        bits(&partial).2,
        want,
        "a missing tile set must change the image"
    );

    // Control: the same part twice overlaps.
    let dup = [parts.clone(), vec![parts[0].clone()]].concat();
    let (code, err) = merge(&dup, &d.join("x.exr"), &[]);
    assert_refused(code, &err, "overlap");

    // Control: a part with another seed, another scene define or another integrator.
    let other = d.join("seed.exr");
    render(&other, &["--tiles", "1/3", "--seed", "7"]);
    let (code, err) = merge(
        &[other, parts[1].clone(), parts[2].clone()],
        &d.join("x.exr"),
        &[],
    );
    assert_refused(code, &err, "seed");
    let other = d.join("define.exr");
    render(&other, &["--tiles", "1/3", "-D", "max_depth=3"]);
    let (code, err) = merge(
        &[other, parts[1].clone(), parts[2].clone()],
        &d.join("x.exr"),
        &[],
    );
    assert_refused(code, &err, "scene hash");
    let other = d.join("integrator.exr");
    render(&other, &["--tiles", "1/3", "--integrator", "direct"]);
    let (code, err) = merge(
        &[other, parts[1].clone(), parts[2].clone()],
        &d.join("x.exr"),
        &[],
    );
    assert_refused(code, &err, "integrator");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn sample_ranges_merge_to_one_render_within_rounding() {
    let d = dir("samples");
    let full = d.join("full.exr");
    render(&full, &["--spp", "6"]);
    let (_, _, want) = bits(&full);
    let ranges = ["0..1", "1..4", "4..6"];
    let parts: Vec<PathBuf> = (0..3).map(|i| d.join(format!("s{i}.exr"))).collect();
    for (r, p) in ranges.iter().zip(&parts) {
        render(p, &["--sample-range", r]);
    }
    let merged = d.join("merged.exr");
    let (code, err) = merge(
        &[parts[2].clone(), parts[0].clone(), parts[1].clone()],
        &merged,
        &["-q"],
    );
    assert_eq!(code, 0, "{err}");
    let (_, _, got) = bits(&merged);
    let mut worst = 0.0f32;
    for (a, b) in got.iter().zip(&want) {
        let (a, b) = (f32::from_bits(*a), f32::from_bits(*b));
        worst = worst.max((a - b).abs() / b.abs().max(1e-3));
    }
    assert!(worst < 1e-5, "relative difference {worst}");

    // A sample-range part and a tile-set part combine: tile set 1/2 with samples 0..3 and
    // 3..6, tile set 2/2 with 0..6.
    let a = d.join("a.exr");
    let b = d.join("b.exr");
    let c = d.join("c.exr");
    render(&a, &["--tiles", "1/2", "--sample-range", "0..3"]);
    render(&b, &["--tiles", "1/2", "--sample-range", "3..6"]);
    render(&c, &["--tiles", "2/2", "--sample-range", "0..6"]);
    let mixed = d.join("mixed.exr");
    let (code, err) = merge(&[a.clone(), b.clone(), c.clone()], &mixed, &["-q"]);
    assert_eq!(code, 0, "{err}");
    let (_, _, got) = bits(&mixed);
    let close = got.iter().zip(&want).all(|(a, b)| {
        let (a, b) = (f32::from_bits(*a), f32::from_bits(*b));
        (a - b).abs() <= 1e-5 * b.abs().max(1e-3)
    });
    assert!(close, "mixed split differs from the whole render");

    // Control: another spp gives other bits (the comparison can fail).
    let five = d.join("five.exr");
    render(&five, &["--spp", "5"]);
    assert_ne!(bits(&five).2, want);

    // Control: a gap (0..1 and 4..6) and an overlap (0..4 with 1..4).
    let (code, err) = merge(&[parts[0].clone(), parts[2].clone()], &d.join("x.exr"), &[]);
    assert_refused(code, &err, "are in no part");
    let big = d.join("big.exr");
    render(&big, &["--sample-range", "0..4"]);
    let (code, err) = merge(&[big, parts[1].clone()], &d.join("x.exr"), &[]);
    assert_refused(code, &err, "overlap");
    // Control: pixels ending at different sample counts.
    let (code, err) = merge(&[a, c], &d.join("x.exr"), &[]);
    assert_refused(code, &err, "same samples");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn merged_parts_merge_again() {
    // Tile sets 1/2 and 2/2 (samples 0..4) merged `--as-part`, then merged with samples 4..8 of
    // the whole image: the same bits as merging the three parts at once.
    let d = dir("remerge");
    let (a, b, c) = (d.join("a.exr"), d.join("b.exr"), d.join("c.exr"));
    render(&a, &["--tiles", "1/2"]);
    render(&b, &["--tiles", "2/2"]);
    render(&c, &["--sample-range", "4..8"]);
    let ab = d.join("ab.exr");
    let (code, err) = merge(&[a.clone(), b.clone()], &ab, &["-q", "--as-part"]);
    assert_eq!(code, 0, "{err}");
    let (twice, once) = (d.join("twice.exr"), d.join("once.exr"));
    let (code, err) = merge(&[ab.clone(), c.clone()], &twice, &["-q"]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = merge(&[a.clone(), b.clone(), c.clone()], &once, &["-q"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        bits(&twice),
        bits(&once),
        "merging in two steps changed the image"
    );
    // Control: the merged part is not just its first half (c alone differs from once).
    assert_ne!(bits(&c).2, bits(&once).2);
    // Control: the merged part holds samples 0..4, so merging it with tile set 1/2 overlaps.
    let (code, err) = merge(&[ab, a.clone()], &d.join("x.exr"), &[]);
    assert_refused(code, &err, "overlap");
    // Control: a part must cover the whole image.
    let (code, err) = merge(&[a], &d.join("x.exr"), &["--as-part", "--allow-missing"]);
    assert_refused(code, &err, "--as-part needs every pixel");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_parts_and_flags_are_one_line_errors() {
    let d = dir("bad");
    let part = d.join("p.exr");
    render(&part, &["--tiles", "1/2"]);
    let bytes = std::fs::read(&part).unwrap();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "garbage.exr",
            b"not an exr file".to_vec(),
            "cannot read EXR header",
        ),
        (
            "truncated.exr",
            bytes[..bytes.len() / 2].to_vec(),
            "cannot decode EXR",
        ),
        ("empty.exr", Vec::new(), "cannot read EXR header"),
    ];
    for (name, data, needle) in cases {
        let p = d.join(name);
        std::fs::write(&p, data).unwrap();
        let (code, err) = merge(&[p], &d.join("x.exr"), &[]);
        assert_refused(code, &err, needle);
    }
    // Every single-byte corruption of the header region either reads or fails cleanly.
    for i in (0..bytes.len().min(1200)).step_by(7) {
        let mut b = bytes.clone();
        b[i] ^= 0x5a;
        let p = d.join("flip.exr");
        std::fs::write(&p, b).unwrap();
        let (code, err) = merge(&[p], &d.join("x.exr"), &["--allow-missing", "-q"]);
        assert!(code == 0 || code == 2, "byte {i}: exit {code}: {err}");
        assert!(!err.contains("panicked"), "byte {i}: {err}");
    }
    // A plain render is not a part.
    let plain = d.join("plain.exr");
    render(&plain, &[]);
    let (code, err) = merge(&[plain], &d.join("x.exr"), &[]);
    assert_refused(code, &err, "not a Tessera part");

    let s = scene();
    let s = s.to_str().unwrap();
    let o = d.join("o.exr");
    let o = o.to_str().unwrap();
    let flags: [(&[&str], &str); 6] = [
        (&["--crop", "0,0,41,10"], "does not fit"),
        (&["--crop", "5,5,5,10"], "x0,y0,x1,y1"),
        (&["--tiles", "0/4"], "K/N"),
        (&["--tiles", "99/99"], "is empty"),
        (&["--sample-range", "4..2"], "a..b"),
        (
            &["--sample-range", "0..4", "--spp", "3"],
            "goes past --spp 3",
        ),
    ];
    for (extra, needle) in flags {
        let mut args = vec!["render", s, "-D", "res=40", "-q", "-o", o];
        args.extend_from_slice(extra);
        let (code, err) = tessera(&args);
        assert_refused(code, &err, needle);
    }
    let _ = std::fs::remove_dir_all(&d);
}

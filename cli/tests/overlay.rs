//! `--overlay`, `--overlay-grid`, `--overlay-crop`: PNG outputs change only inside the label band,
//! on the grid lines and on the rectangle's edge (and do change there); EXR outputs are the same
//! bytes with or without an overlay.

use std::path::{Path, PathBuf};
use std::process::Command;
use tessera::overlay::{label_band, line_width, parse_crop};

const BIN: &str = env!("CARGO_BIN_EXE_tessera");

fn render(dir: &Path, tag: &str, extra: &[&str]) -> (PathBuf, PathBuf) {
    let (png, exr) = (
        dir.join(format!("{tag}.png")),
        dir.join(format!("{tag}.exr")),
    );
    let o = Command::new(BIN)
        .arg("render")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cbox.xml"))
        .args([
            "-D",
            "res=96",
            "--spp",
            "2",
            "--tile-size",
            "16",
            "-q",
            "-o",
        ])
        .arg(&png)
        .arg("-o")
        .arg(&exr)
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (png, exr)
}

#[test]
fn overlay_touches_only_its_pixels_and_never_exr() {
    check_overlay("progressive", &[]);
}

#[test]
fn one_pass_renders_draw_overlays_too() {
    // `--stats` renders in one pass (cli/render_once.rs), through another writer.
    check_overlay("stats", &["--stats"]);
}

/// Renders with and without the three overlays (both with `extra`) and checks which pixels
/// changed.
fn check_overlay(tag: &str, extra: &[&str]) {
    let dir = std::env::temp_dir().join(format!("tessera-overlay-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (plain_png, plain_exr) = render(&dir, "plain", extra);
    let crop = [10u32, 12, 40, 50];
    let mut args = vec![
        "--overlay",
        "--overlay-grid",
        "--overlay-crop",
        "10,12,40,50",
    ];
    args.extend(extra);
    let (ov_png, ov_exr) = render(&dir, "overlay", &args);
    assert_eq!(
        std::fs::read(&plain_exr).unwrap(),
        std::fs::read(&ov_exr).unwrap(),
        "the overlay changed the EXR"
    );
    let a = image::open(&plain_png).unwrap().to_rgb8();
    let b = image::open(&ov_png).unwrap().to_rgb8();
    let _ = std::fs::remove_dir_all(&dir);
    let (w, h) = a.dimensions();
    let (band, lw) = (label_band(w, h), line_width(w, h));
    assert!(band > h / 2 && band < h, "band starts at row {band} of {h}");
    let grid = |x: u32, y: u32| (x % 16 < lw && x > 0) || (y % 16 < lw && y > 0);
    let [x0, y0, x1, y1] = crop;
    let edge = |x: u32, y: u32| {
        (x0..x1).contains(&x)
            && (y0..y1).contains(&y)
            && (x < x0 + lw || x + lw >= x1 || y < y0 + lw || y + lw >= y1)
    };
    let (mut in_band, mut on_grid, mut on_edge) = (0, 0, 0);
    for y in 0..h {
        for x in 0..w {
            if a.get_pixel(x, y) == b.get_pixel(x, y) {
                continue;
            }
            if y >= band {
                in_band += 1;
            } else if edge(x, y) {
                on_edge += 1;
            } else if grid(x, y) {
                on_grid += 1;
            } else {
                panic!("pixel ({x}, {y}) changed outside the overlay");
            }
        }
    }
    // Controls: each part did draw something.
    assert!(
        in_band > (h - band) * w / 2,
        "label band barely changed: {in_band}"
    );
    assert!(on_edge > 2 * (x1 - x0), "rectangle not drawn: {on_edge}");
    assert!(on_grid > 5 * w, "grid not drawn: {on_grid}");
}

#[test]
fn crop_argument_is_checked() {
    assert_eq!(parse_crop("1,2,3,4"), Ok([1, 2, 3, 4]));
    for bad in [
        "1,2,3",
        "3,2,1,4",
        "1,4,3,4",
        "a,b,c,d",
        "1,2,3,4,5",
        "-1,2,3,4",
    ] {
        assert!(parse_crop(bad).is_err(), "{bad}");
    }
}

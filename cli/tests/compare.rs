//! `tessera compare` on tiny hand-made images whose errors are known in closed form, its JSON
//! output, its difference image, and its errors (one line, exit code 2).
use std::path::{Path, PathBuf};
use std::process::Command;
use tessera::image_io::{read_image, write_image, RgbImage};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tessera-compare-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(path: &Path, width: u32, data: Vec<[f32; 3]>) {
    let height = data.len() as u32 / width;
    write_image(
        path,
        &RgbImage {
            width,
            height,
            data,
        },
    )
    .unwrap();
}

/// Runs `tessera compare ARGS`; returns (exit code, stdout, stderr).
fn compare(args: &[&Path], extra: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_tessera"))
        .arg("compare")
        .args(args)
        .args(extra)
        .output()
        .expect("run tessera");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The number after `"key": ` in a flat JSON object.
fn field(json: &str, key: &str) -> f64 {
    let pat = format!("\"{key}\": ");
    let start = json.find(&pat).unwrap_or_else(|| panic!("{key} in {json}")) + pat.len();
    let rest = &json[start..];
    let end = rest.find([',', '}', ']']).unwrap();
    rest[..end].trim().parse().unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * b.abs().max(1e-6)
}

#[test]
fn known_errors_of_two_tiny_images() {
    let d = dir("known");
    let (a, b) = (d.join("a.pfm"), d.join("b.pfm"));
    // Pixel 0 differs by (0, 1, 2) on a reference of 1; pixel 1 by -0.1 on a reference of 0.1;
    // pixel 2 is infinite in A and so is left out.
    write(
        &a,
        3,
        vec![[1.0, 2.0, 3.0], [0.0, 0.0, 0.0], [f32::INFINITY, 0.0, 0.0]],
    );
    write(
        &b,
        3,
        vec![[1.0, 1.0, 1.0], [0.1, 0.1, 0.1], [5.0, 5.0, 5.0]],
    );
    let (code, out, err) = compare(&[&a, &b], &["--json"]);
    assert_eq!(code, 0, "{err}");
    let b1 = 0.1f32 as f64; // the stored reference value
    let se = 1.0 + 4.0 + 3.0 * b1 * b1;
    assert!(close(field(&out, "rmse"), (se / 6.0).sqrt()), "{out}");
    let rel = (1.0 + 4.0) / 1.01 + 3.0 * b1 * b1 / (b1 * b1 + 0.01);
    assert!(close(field(&out, "relmse"), rel / 6.0), "{out}");
    assert!(close(field(&out, "mae"), (3.0 + 3.0 * b1) / 6.0), "{out}");
    assert!(close(field(&out, "max_abs_error"), 2.0), "{out}");
    assert!(out.contains("\"max_abs_error_at\": [0, 0]"), "{out}");
    assert!(out.contains("\"max_abs_error_channel\": \"B\""), "{out}");
    assert_eq!(field(&out, "nonfinite_a"), 1.0);
    assert_eq!(field(&out, "nonfinite_b"), 0.0);
    // Means over the two pixels finite in both: A = (0.5, 1, 1.5), B = (0.55, ...).
    assert!(out.contains("\"mean_a\": [0.5, 1.0, 1.5]"), "{out}");
    assert!(close(field(&out, "width"), 3.0) && close(field(&out, "height"), 1.0));

    // Text output carries the same numbers.
    let (code, text, _) = compare(&[&a, &b], &[]);
    assert_eq!(code, 0);
    assert!(
        text.contains("relMSE") && text.contains("max abs error"),
        "{text}"
    );

    // Control: an image against itself has no error; changing one value changes the RMSE.
    let (_, same, _) = compare(&[&b, &b], &["--json"]);
    assert_eq!(field(&same, "rmse"), 0.0);
    assert_eq!(field(&same, "relmse"), 0.0);
    let c = d.join("c.pfm");
    write(
        &c,
        3,
        vec![[1.0, 2.0, 3.5], [0.0, 0.0, 0.0], [f32::INFINITY, 0.0, 0.0]],
    );
    let (_, other, _) = compare(&[&c, &b], &["--json"]);
    assert!(!close(field(&other, "rmse"), (se / 6.0).sqrt()));

    // The difference image: a PNG larger than the (enlarged) image, with its bar beside it.
    let png = d.join("diff.png");
    let (code, _, err) = compare(&[&a, &b], &["--diff", png.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let img = read_image(&png).unwrap();
    assert!(
        img.width > 3 * 16 && img.height > 16,
        "{}x{}",
        img.width,
        img.height
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn errors_are_one_line_with_exit_code_2() {
    let d = dir("errors");
    let (a, b) = (d.join("a.pfm"), d.join("b.pfm"));
    write(&a, 2, vec![[0.0; 3]; 4]);
    write(&b, 4, vec![[0.0; 3]; 4]);
    let bad = d.join("bad.exr");
    std::fs::write(&bad, b"not an image").unwrap();
    let missing = d.join("missing.pfm");
    let cases: [(&Path, &Path, &str); 3] = [
        (&a, &b, "differ in size: 2x2 and 4x1"),
        (&bad, &a, "cannot read image"),
        (&a, &missing, "cannot read image"),
    ];
    for (x, y, needle) in cases {
        let (code, out, err) = compare(&[x, y], &[]);
        assert_eq!(code, 2, "{err}");
        assert!(out.is_empty(), "{out}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{err}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

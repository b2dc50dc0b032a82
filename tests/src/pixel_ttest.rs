//! Student t-tests of a one-pixel render against a closed form, per channel: what the media
//! tests (`media_analytic.rs`, `hetero_analytic.rs`) check each scene with, and the control
//! that a wrong expected value must fail.
use crate::{load_xml, render_loaded, t_test_f32};
use tessera_lab::stats::sidak_alpha;

/// Renders `xml` (a scene of one pixel) with `spp` samples; the smallest p-value of the
/// pixel's three channels against `expected`.
pub fn pixel_p_value(xml: &str, spp: u64, expected: [f64; 3]) -> f64 {
    let loaded = load_xml(xml, &[]);
    let fb = render_loaded(&loaded, spp, 5);
    let p = fb.at(0, 0);
    assert_eq!(p.dropped, 0, "non-finite samples");
    let n = p.count as f64;
    (0..3)
        .map(|k| {
            let mean = p.sum[k] / n;
            let var = ((p.sum_sq[k] - n * mean * mean) / (n - 1.0)).max(0.0);
            let (t, pv) = t_test_f32(n, mean, var, expected[k]);
            println!(
                "  channel {k}: mean {mean:.6} expected {:.6} t = {t:.3} p = {pv:.3e}",
                expected[k]
            );
            pv
        })
        .fold(1.0, f64::min)
}

/// Asserts the pixel agrees with `expected` at significance 0.01, Sidak-corrected over the
/// `n_tests` channel tests of the caller's file.
pub fn check_pixel(label: &str, xml: &str, spp: u64, expected: [f64; 3], n_tests: usize) {
    println!("{label}");
    let p = pixel_p_value(xml, spp, expected);
    let alpha = sidak_alpha(0.01, n_tests);
    assert!(p >= alpha, "{label}: p = {p:.3e} < {alpha:.3e}");
}

/// Asserts the pixel disagrees with the `wrong` value (p below 1e-6).
pub fn control_pixel(label: &str, xml: &str, spp: u64, wrong: [f64; 3]) {
    println!("control: {label}");
    let p = pixel_p_value(xml, spp, wrong);
    assert!(p < 1e-6, "control {label} passed: p = {p:.3e}");
}

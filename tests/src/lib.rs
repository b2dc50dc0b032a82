//! Shared helpers of Tessera's integration and statistical tests: render a scene given as XML
//! text, and turn per-pixel sums into the numbers statistical tests need.
use std::path::{Path, PathBuf};
use tessera::render::{render, Framebuffer, RenderOptions};
use tessera::scene::{load_scene, load_scene_str, LoadedScene};

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

/// Renders a loaded scene with `spp` samples on 2 threads.
pub fn render_loaded(l: &LoadedScene, spp: u64, seed: u64) -> Framebuffer {
    let opts = RenderOptions {
        samples: 0..spp,
        threads: 2,
        tile_size: 16,
        seed,
    };
    render(&l.scene, &l.integrator, &opts, &mut |_, _| {})
}

/// Mean and variance of the mean of a block of pixels, per channel. Pixels are strata: the
/// variance is the sum of each pixel's sample variance over its sample count, over the pixel
/// count squared.
pub fn region_stats(fb: &Framebuffer, x0: u32, y0: u32, w: u32, h: u32) -> [(f64, f64); 3] {
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

//! Tessera as a library: load a scene file, render it on all cores, write a PNG, and report the
//! image's mean. The same bits for any thread count.
//!
//! Run: `cargo run --release --example render_scene -- [SCENE.xml] [OUT.png] [SPP]`
//! (defaults: `scenes/cbox.xml`, `render_scene.png`, 16).
use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene_path = args
        .next()
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("scenes/cbox.xml"));
    let out = args.next().unwrap_or_else(|| "render_scene.png".into());
    let spp = args.next().and_then(|s| s.parse().ok()).unwrap_or(16);

    let scene = match tessera::load(&scene_path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let options = tessera::Options {
        spp: Some(spp),
        ..Default::default()
    };
    let image = tessera::render(&scene, &options);
    let n = image.data.len() as f64;
    let mean: Vec<f64> = (0..3)
        .map(|k| image.data.iter().map(|p| p[k] as f64).sum::<f64>() / n)
        .collect();
    println!(
        "{}x{} at {spp} spp: mean RGB {:.4} {:.4} {:.4}",
        image.width, image.height, mean[0], mean[1], mean[2]
    );
    if let Err(e) = tessera::image_io::write_image(out.as_ref(), &image) {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    ExitCode::SUCCESS
}

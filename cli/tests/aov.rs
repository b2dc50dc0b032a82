//! `tessera render` of a scene with the `aov` integrator: the EXR output holds the colour and
//! every extra channel under Mitsuba 3's names (read back with the `exr` crate through
//! `tessera::layers::read_channels_exr`); a PNG output holds the colour, with one warning; flags
//! the extra channels do not support are a one-line error.
use std::path::Path;
use tessera::layers::read_channels_exr;

use crate::support;
use support::{run, stderr};

#[test]
fn render_writes_mitsuba_channel_names_to_exr() {
    let dir = std::env::temp_dir().join(format!("tessera-aov-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/aov/aov.xml");
    let (exr, png) = (dir.join("out.exr"), dir.join("out.png"));
    let o = run(&[
        "render",
        scene.to_str().unwrap(),
        "--spp",
        "4",
        "--quiet",
        "-o",
        exr.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let warnings: Vec<&str> = err.lines().filter(|l| l.contains("warning")).collect();
    assert_eq!(warnings.len(), 1, "{err}");
    assert!(warnings[0].contains("out.png") && warnings[0].contains("14 extra channels"));
    let (w, h, channels) = read_channels_exr(&exr).unwrap();
    assert_eq!((w, h), (32, 32));
    let names: Vec<&str> = channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "B", "G", "R", "alb.B", "alb.G", "alb.R", "dd.y.T", "img.A", "img.B", "img.G", "img.R",
            "nn.X", "nn.Y", "nn.Z", "pos.X", "pos.Y", "pos.Z"
        ]
    );
    // The colour is the nested path tracer's, so R and img.R are the same values; depth is a
    // distance (about 4 from the camera), alpha is 1 (the sky counts as covered).
    let get = |n: &str| &channels.iter().find(|c| c.name == n).unwrap().values;
    assert_eq!(get("R"), get("img.R"));
    assert!(get("img.A").iter().all(|&a| a == 1.0));
    let depth = get("dd.y.T");
    assert!(depth
        .iter()
        .all(|d| d.is_finite() && (0.0..10.0).contains(d)));
    assert!(depth.iter().any(|&d| d > 3.0));
    assert!(png.exists());
    // Flags the extra channels do not support: one line, naming the scene.
    let o = run(&[
        "render",
        scene.to_str().unwrap(),
        "--time",
        "1",
        "-o",
        dir.join("t.exr").to_str().unwrap(),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("aov.xml") && err.contains("--time"), "{err}");
    assert!(!dir.join("t.exr").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

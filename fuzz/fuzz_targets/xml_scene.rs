//! Fuzz target: scene XML text -> loaded scene -> one sample of a few pixels.
//!
//! Loading must end in `Ok` or a one-line `InputError`, never a panic, a hang or a huge
//! allocation. A scene that loads is rendered at 1 sample per pixel on three pixels only (the
//! harness does not render whole films, so big films stay cheap), and every pixel mean must be
//! finite. Includes and mesh files resolve in a scratch directory (see `common.rs`).
#![no_main]
use libfuzzer_sys::fuzz_target;
use tessera_core::film::PixelAccum;
use tessera_core::render::RenderJob;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = common::dir().join("scene.xml");
    let loaded = match tessera_scene::load_scene_str(text, &path, &[]) {
        Ok(l) => l,
        Err(e) => {
            assert!(!e.to_string().contains('\n'), "multi-line error: {e}");
            return;
        }
    };
    let cam = &loaded.scene.camera;
    let (w, h) = (cam.width, cam.height);
    assert!(w >= 1 && h >= 1, "empty film {w}x{h}");
    for (x, y) in [(0, 0), (w / 2, h / 2), (w - 1, h - 1)] {
        let mut acc = PixelAccum::default();
        RenderJob::new(&loaded.scene, &loaded.integrator, loaded.seed).accumulate(x, y, 0..1, &mut acc);
        assert!(
            acc.mean().iter().all(|c| c.is_finite()),
            "non-finite pixel ({x}, {y})"
        );
    }
});

//! Part files: round trips, and parts of the older format.
use super::*;

/// A part keeps every word of its pixels, the ray counts among them; a version 1 part
/// (written without them) reads with counts of 0; another version is refused.
#[test]
fn parts_keep_the_ray_counts_and_old_parts_read_without_them() {
    let mut fb = Framebuffer::new(3, 2);
    for (i, p) in fb.pixels.iter_mut().enumerate() {
        *p = PixelAccum {
            sum: [i as f64 * 0.5, 1.0, 2.0],
            sum_sq: [3.0, 4.0, i as f64],
            count: i as u64 + 1,
            dropped: 1,
            rays: 7 * i as u64 + 3,
        };
    }
    let info = PartInfo {
        width: 3,
        height: 2,
        selection: PixelSelection::default(),
        tile_size: 32,
        samples: 0..4,
        seed: 9,
        integrator: "test".into(),
        scene_hash: 0xabc,
    };
    let dir = std::env::temp_dir().join(format!("tessera-part-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("p.exr");
    write_part(&path, &info, &fb).unwrap();
    let back = read_part(&path).unwrap();
    assert_eq!((back.info, back.pixels), (info.clone(), fb.pixels.clone()));
    write_version(&path, &info, &fb, "1", PixelAccum::WORDS - 1).unwrap();
    let old = read_part(&path).unwrap();
    for (p, q) in old.pixels.iter().zip(&fb.pixels) {
        assert_eq!(*p, PixelAccum { rays: 0, ..*q });
    }
    write_version(&path, &info, &fb, "3", PixelAccum::WORDS).unwrap();
    let e = read_part(&path).err().unwrap();
    assert!(e.contains("unsupported part version 3"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

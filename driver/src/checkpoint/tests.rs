//! The checkpoint format's own tests.
use super::*;
use crate::progressive::check::CheckState;

#[test]
fn fnv_reference_values() {
    // Published FNV-1a 64 test vectors.
    let mut h = Fnv1a::default();
    h.update(b"");
    assert_eq!(h.0, 0xcbf29ce484222325);
    h.update(b"a");
    assert_eq!(h.0, 0xaf63dc4c8601ec8c);
    let mut h = Fnv1a::default();
    h.update(b"foobar");
    assert_eq!(h.0, 0x85944171f73967e8);
}

#[test]
fn defines_order_does_not_matter_but_values_do() {
    let d = |v: &[(&str, &str)]| -> Vec<(String, String)> {
        v.iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    };
    let a = scene_hash(b"x", &d(&[("a", "1"), ("b", "2")]));
    assert_eq!(a, scene_hash(b"x", &d(&[("b", "2"), ("a", "1")])));
    assert_ne!(a, scene_hash(b"x", &d(&[("a", "1"), ("b", "3")])));
    assert_ne!(a, scene_hash(b"y", &d(&[("a", "1"), ("b", "2")])));
    // Length prefixes: moving a byte between name and value changes the hash.
    assert_ne!(
        scene_hash(b"", &d(&[("ab", "c")])),
        scene_hash(b"", &d(&[("a", "bc")]))
    );
}

/// Rewrites the checksum after a change to the body.
fn resum(mut b: Vec<u8>) -> Vec<u8> {
    let end = b.len() - 8;
    let mut h = Fnv1a::default();
    h.update(&b[..end]);
    b[end..].copy_from_slice(&h.0.to_le_bytes());
    b
}

/// `bytes` with the last `cut` bytes before the checksum removed, as version `version`.
fn older(bytes: &[u8], cut: usize, version: u32) -> Vec<u8> {
    let mut b = bytes[..bytes.len() - 8 - cut].to_vec();
    b[8..12].copy_from_slice(&version.to_le_bytes());
    b.extend_from_slice(&[0; 8]);
    resum(b)
}

#[test]
fn round_trip_and_every_damage_is_caught() {
    let meta = CheckpointMeta {
        width: 3,
        height: 2,
        seed: 7,
        target_spp: 16,
        scene_hash: 0x1234,
        passes: 3,
        seconds: 1.5,
        integrator: "Path(max_depth: 8)".into(),
    };
    let pixels: Vec<PixelAccum> = (0..6)
        .map(|i| PixelAccum {
            sum: [i as f64, 0.5, 1e300],
            sum_sq: [1.0, 2.0, 3.0],
            count: i,
            dropped: 1,
        })
        .collect();
    let targets: Vec<u64> = (0..6).map(|i| 2 * i + 1).collect();
    let check = CheckState {
        spp: 4,
        estimate: Some(2.5e-3),
        pixels: pixels
            .iter()
            .map(|p| PixelAccum {
                count: p.count / 2,
                sum: [0.25; 3],
                ..*p
            })
            .collect(),
    };
    let path = std::env::temp_dir().join(format!("tessera-ckpt-{}.bin", std::process::id()));
    let write = |more: Continuation| {
        write_checkpoint(&path, &meta, &pixels, more).unwrap();
        std::fs::read(&path).unwrap()
    };
    let bytes = write(Continuation::default());
    let with_targets = write(Continuation {
        pending: Some(&targets),
        check: None,
        splats: None,
    });
    let with_both = write(Continuation {
        pending: Some(&targets),
        check: Some(&check),
        splats: None,
    });
    let no_estimate = CheckState {
        estimate: None,
        ..check.clone()
    };
    let with_check = write(Continuation {
        pending: None,
        check: Some(&no_estimate),
        splats: None,
    });
    let mut splats = crate::splats::Splats::new(1, pixels.len());
    for (i, v) in splats.sums.iter_mut().enumerate() {
        *v = i as f32 * 0.25 - 3.0;
    }
    let with_splats = write(Continuation {
        pending: Some(&targets),
        check: Some(&check),
        splats: Some(&splats),
    });
    let _ = std::fs::remove_file(&path);
    let back = read_checkpoint(&bytes).unwrap();
    assert_eq!(back.meta, meta);
    assert_eq!(back.pixels, pixels);
    assert_eq!((back.pending, back.check), (None, None));
    let back = read_checkpoint(&with_targets).unwrap();
    assert_eq!((back.meta, back.pixels), (meta.clone(), pixels.clone()));
    assert_eq!(back.pending.as_deref(), Some(&targets[..]));
    assert_eq!(back.check, None);
    let back = read_checkpoint(&with_both).unwrap();
    assert_eq!(back.pixels, pixels);
    assert_eq!(back.pending.as_deref(), Some(&targets[..]));
    assert_eq!(back.check.as_ref(), Some(&check));
    let back = read_checkpoint(&with_check).unwrap();
    assert_eq!((back.pending, back.check), (None, Some(no_estimate)));
    assert_eq!(back.splats, None);
    let back = read_checkpoint(&with_splats).unwrap();
    assert_eq!(back.check.as_ref(), Some(&check));
    assert_eq!(back.splats.as_ref(), Some(&splats.sums));
    // Versions 1 (no targets section), 2 (no check point section) and 3 (no splatted sums) are
    // still read.
    assert_eq!(
        read_checkpoint(&older(&bytes, 24, 1)).unwrap().pixels,
        pixels
    );
    let v2 = read_checkpoint(&older(&with_targets, 16, 2)).unwrap();
    assert_eq!(v2.pending.as_deref(), Some(&targets[..]));
    let v3 = read_checkpoint(&older(&with_both, 8, 3)).unwrap();
    assert_eq!(v3.check.as_ref(), Some(&check));
    // Splatted sums that are not finite are refused.
    let mut inf = with_splats.clone();
    let last_sum = inf.len() - 8 - 4;
    inf[last_sum..last_sum + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert!(read_checkpoint(&resum(inf))
        .unwrap_err()
        .contains("pixel (2, 1) holds impossible splatted sums"));
    // Values that only a damaged or hostile file holds (with a valid checksum) are refused: a
    // pass target below a pixel's count, a check point pixel with more samples than the pixel
    // now, a negative estimate, a check point at 0 spp.
    let n = with_both.len();
    let mut low = with_targets.clone();
    let at = low.len() - 24 - 8 * 6;
    low[at..at + 8].copy_from_slice(&0u64.to_le_bytes());
    let err = |b: Vec<u8>| read_checkpoint(&resum(b)).unwrap_err();
    assert!(err(low).contains("below its sample count"));
    let mut more = with_both.clone();
    let last_count = n - 8 - 8 - 16;
    more[last_count..last_count + 8].copy_from_slice(&99u64.to_le_bytes());
    assert!(err(more).contains("check point pixel (2, 1)"));
    let estimate_at = n - 8 - 8 - 64 * 6 - 8;
    let mut negative = with_both.clone();
    negative[estimate_at..estimate_at + 8].copy_from_slice(&(-1.0f64).to_le_bytes());
    assert!(err(negative).contains("estimate -1"));
    let mut zero = with_both.clone();
    zero[estimate_at - 8..estimate_at].copy_from_slice(&0u64.to_le_bytes());
    assert!(err(zero).contains("at 0 spp"));
    for bytes in [&with_splats, &with_both, &with_targets, &with_check, &bytes] {
        for len in 0..bytes.len() {
            assert!(
                read_checkpoint(&bytes[..len]).is_err(),
                "truncated to {len}"
            );
        }
        for i in 0..bytes.len() {
            for bit in [0x01u8, 0x80] {
                let mut b = bytes.clone();
                b[i] ^= bit;
                assert!(
                    read_checkpoint(&b).is_err(),
                    "byte {i} bit {bit:#x} flipped"
                );
            }
        }
    }
    // A huge size in the header with a matching checksum: rejected by length, no allocation.
    let mut b = bytes.clone();
    b[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    b[16..20].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(err(b).contains("truncated"));
}

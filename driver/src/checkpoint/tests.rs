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

/// Bytes after the last section: the sampler's set-up count and the checksum.
const TAIL: usize = 16;

/// A version 6 checkpoint in version 5's layout: without the sampler's set-up count.
fn v5(bytes: &[u8]) -> Vec<u8> {
    let mut b = bytes[..bytes.len() - TAIL].to_vec();
    b.extend_from_slice(&[0; 8]);
    b[8..12].copy_from_slice(&5u32.to_le_bytes());
    resum(b)
}

/// A version 6 checkpoint of `pixels` pixels in version 4's layout: every pixel record (and
/// every check point record) without its last word, the ray count, and no set-up count.
fn without_rays(bytes: &[u8], pixels: usize) -> Vec<u8> {
    let bytes = &v5(bytes)[..];
    let n = u32::from_le_bytes(bytes[60..64].try_into().unwrap()) as usize;
    let word = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
    let mut b = bytes[..64 + n].to_vec();
    let records = |b: &mut Vec<u8>, at: usize| {
        for i in 0..pixels {
            b.extend_from_slice(&bytes[at + 72 * i..at + 72 * i + 64]);
        }
        at + 72 * pixels
    };
    let at = records(&mut b, 64 + n);
    let targets = word(at);
    let at = at + 8 + 8 * targets;
    b.extend_from_slice(&bytes[at - 8 - 8 * targets..at]);
    let checks = word(at);
    let at = match checks {
        0 => {
            b.extend_from_slice(&bytes[at..at + 8]);
            at + 8
        }
        _ => {
            b.extend_from_slice(&bytes[at..at + 24]);
            records(&mut b, at + 24)
        }
    };
    b.extend_from_slice(&bytes[at..]);
    b[8..12].copy_from_slice(&4u32.to_le_bytes());
    resum(b)
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
        sampler_spp: 64,
    };
    let pixels: Vec<PixelAccum> = (0..6)
        .map(|i| PixelAccum {
            sum: [i as f64, 0.5, 1e300],
            sum_sq: [1.0, 2.0, 3.0],
            count: i,
            dropped: 1,
            rays: 3 * i + 2,
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
    // Versions 1 (no targets section), 2 (no check point section), 3 (no splatted sums), 4
    // (no ray counts, read as 0) and 5 (no set-up count, read as 0) are still read.
    let v5_back = read_checkpoint(&v5(&with_splats)).unwrap();
    assert_eq!(v5_back.meta.sampler_spp, 0);
    assert_eq!(v5_back.pixels, pixels);
    assert_eq!(v5_back.splats.as_ref(), Some(&splats.sums));
    assert_eq!(read_checkpoint(&v5(&bytes)).unwrap().pixels, pixels);
    // Control: a version 6 file labelled 5 is refused (wrong length).
    let mut relabelled = with_splats.clone();
    relabelled[8..12].copy_from_slice(&5u32.to_le_bytes());
    assert!(read_checkpoint(&resum(relabelled)).is_err());
    let uncounted = |p: &[PixelAccum]| -> Vec<PixelAccum> {
        p.iter().map(|p| PixelAccum { rays: 0, ..*p }).collect()
    };
    let v4 = read_checkpoint(&without_rays(&with_splats, 6)).unwrap();
    assert_eq!(v4.pixels, uncounted(&pixels));
    assert_eq!(v4.pending.as_deref(), Some(&targets[..]));
    assert_eq!(v4.check.map(|c| c.pixels), Some(uncounted(&check.pixels)));
    assert_eq!(v4.splats.as_ref(), Some(&splats.sums));
    assert_eq!(
        read_checkpoint(&older(&without_rays(&bytes, 6), 24, 1))
            .unwrap()
            .pixels,
        uncounted(&pixels)
    );
    let v2 = read_checkpoint(&older(&without_rays(&with_targets, 6), 16, 2)).unwrap();
    assert_eq!(v2.pending.as_deref(), Some(&targets[..]));
    let v3 = read_checkpoint(&older(&without_rays(&with_both, 6), 8, 3)).unwrap();
    assert_eq!(v3.check.map(|c| c.pixels), Some(uncounted(&check.pixels)));
    // Control: a version 5 file's records read as version 4 are refused (wrong length).
    let mut relabelled = v5(&with_both);
    relabelled[8..12].copy_from_slice(&4u32.to_le_bytes());
    assert!(read_checkpoint(&resum(relabelled)).is_err());
    // Splatted sums that are not finite are refused.
    let mut inf = with_splats.clone();
    let last_sum = inf.len() - TAIL - 4;
    inf[last_sum..last_sum + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert!(read_checkpoint(&resum(inf))
        .unwrap_err()
        .contains("pixel (2, 1) holds impossible splatted sums"));
    // Values that only a damaged or hostile file holds (with a valid checksum) are refused: a
    // pass target below a pixel's count, a check point pixel with more samples than the pixel
    // now, a negative estimate, a check point at 0 spp.
    let n = with_both.len();
    let mut low = with_targets.clone();
    let at = low.len() - TAIL - 16 - 8 * 6;
    low[at..at + 8].copy_from_slice(&0u64.to_le_bytes());
    let err = |b: Vec<u8>| read_checkpoint(&resum(b)).unwrap_err();
    assert!(err(low).contains("below its sample count"));
    let mut more = with_both.clone();
    let last_count = n - TAIL - 8 - 24;
    more[last_count..last_count + 8].copy_from_slice(&99u64.to_le_bytes());
    assert!(err(more).contains("check point pixel (2, 1)"));
    let estimate_at = n - TAIL - 8 - 72 * 6 - 8;
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

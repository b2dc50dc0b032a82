//! Ray casts in the Cornell box, the benchmark scene Tessera trails Mitsuba 3 on: Tessera's own
//! casts (`Scene::intersect_hit`, `Scene::occluded`: cbox's hierarchy is one 8-wide node) against
//! Embree 3 one ray at a time (`rtcIntersect1`, `rtcOccluded1`) and in packets of 8 and 16 rays
//! (`rtcIntersect8/16`, `rtcOccluded8/16`), which is how Mitsuba 3's `llvm_ad_rgb` traces: it hands
//! Embree packets as wide as its vector registers (16 lanes with AVX-512). The question it
//! answers: how much of Mitsuba's lead in samples per second on cbox is in casting rays?
//!
//! Rays as the path loop casts them: from points where uniform random rays inside the box hit a
//! surface, a continuation ray (uniform over the hemisphere the hit was seen from, closest hit)
//! and a shadow segment to a uniform point on the light (any hit), both with Tessera's own ray
//! offsets; the packets take consecutive rays, so they are as incoherent as the path loop's.
//! The `px` rows are the first vertex of one pixel's samples instead (16 jittered camera rays of
//! a random pixel, then each hit's continuation ray and shadow segment), consecutive, so a
//! packet holds one pixel's samples, as it would in a renderer that packs them that way.
//! Embree one ray at a time also runs in its robust mode (`embreeR1`, `RTC_SCENE_FLAG_ROBUST`: a
//! watertight triangle test and conservative node tests, the guarantees Tessera's casts give).
//! `embreeM1` / `embreeM16` set Embree up as Mitsuba 3 does (`scripts/mitsuba_rays/run.sh` prints
//! its settings): high build quality, and the camera rays' packets marked coherent.
//! With `--replay PREFIX`, two more rows cast the packets Mitsuba 3 itself cast, recorded by
//! `RAYDUMP=PREFIX scripts/mitsuba_rays/run.sh SCENE.xml ...` (`mi closest`, `mi shadow`): the
//! 16-wide columns cast Mitsuba's packets exactly as recorded (mask, idle lanes and, in
//! `embreeM16`, the context flags), the 8-wide one each packet's active rays eight at a time,
//! the others its rays one at a time.
//! Rays per second of one thread, best of 5 alternating rounds; the hit counts of all casts must
//! agree (it panics otherwise).
//!
//! `cargo bench -p tessera-benches --features embree --bench embree_small [-- SCENE.xml]
//! [--replay PREFIX]` (default `scenes/cbox.xml`; any scene of triangles only). Needs Embree 3
//! (`scripts/install_embree.sh`); `--features embree-mitsuba` links the Embree in Mitsuba's wheel
//! instead (see `benches/Cargo.toml`).
mod embree_ffi;

use embree_ffi::{Embree, Mode, RawPacket16};
use glam::{Vec2, Vec3};
use std::path::Path;
use std::time::Instant;
use tessera_benches::Rng;
use tessera_core::emitter::Emitter;
use tessera_core::geometry::{Interaction, Prim};
use tessera_core::math::Ray;
use tessera_core::scene::Scene;
use tessera_scene::load_scene;

/// Rays cast per second by `cast`, which takes a chunk (a few rays, or a packet) and returns
/// how many hit: best of `rounds` rounds of at least 0.2 s each over `chunks`, which hold `rays`
/// rays in all; also the hit count of one pass.
fn rate<T>(
    chunks: &[T],
    rays: usize,
    rounds: usize,
    mut cast: impl FnMut(&T) -> usize,
) -> (f64, usize) {
    let hits: usize = chunks.iter().map(&mut cast).sum();
    let mut best = 0.0f64;
    for _ in 0..rounds {
        let start = Instant::now();
        let mut passes = 0usize;
        let mut found = 0usize;
        while passes == 0 || start.elapsed().as_secs_f64() < 0.2 {
            for c in chunks {
                found += cast(std::hint::black_box(c));
            }
            passes += 1;
        }
        std::hint::black_box(found);
        best = best.max((passes * rays) as f64 / start.elapsed().as_secs_f64());
    }
    (best, hits)
}

/// A packet for the 16-wide columns: consecutive rays, or a packet as a renderer recorded it.
enum Packet16<'a> {
    Rays(&'a [Ray]),
    Recorded(&'a RawPacket16),
}

/// Packets that Mitsuba 3 cast, as `scripts/mitsuba_rays/run.sh` records them (`RAYDUMP`): per
/// 16-wide call, the valid mask (16 `i32`), the `RTCRay16` before the call (12 fields of 16
/// words) and 16 words whose first is the call's context flags. Returns each packet's active
/// lanes as rays, and the packet as recorded.
fn recorded_packets(file: &Path) -> Vec<(Vec<Ray>, RawPacket16)> {
    let bytes = std::fs::read(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    const RECORD: usize = 4 * 16 * 14;
    assert!(
        bytes.len().is_multiple_of(RECORD),
        "{}: not a whole number of packets",
        file.display()
    );
    bytes
        .chunks(RECORD)
        .map(|rec| {
            let words: Vec<u32> = rec
                .chunks(4)
                .map(|w| u32::from_le_bytes(w.try_into().unwrap()))
                .collect();
            let (valid, rest) = words.split_at(16);
            let (ray, context) = rest.split_at(16 * 12);
            let valid: [i32; 16] = core::array::from_fn(|i| valid[i] as i32);
            let raw = RawPacket16::from_words(&valid, ray.try_into().unwrap(), context[0]);
            (raw.rays(), raw)
        })
        .collect()
}

/// A row of the table: its name, its rays, the packets they came in (when recorded), and
/// whether they are any-hit queries.
type RaySet<'a> = (
    &'static str,
    Vec<Ray>,
    Option<&'a [(Vec<Ray>, RawPacket16)]>,
    bool,
);

/// Closest hits of a 16-wide packet: how many of its rays hit. `as_mitsuba`: mark the packet
/// coherent where Mitsuba 3 does (`coherent`: camera rays; a recorded packet: its recorded flags).
fn intersect16(e: &Embree, p: &Packet16, as_mitsuba: bool, coherent: bool) -> usize {
    match p {
        Packet16::Rays(r) if as_mitsuba && coherent => e.intersect16_coherent(r),
        Packet16::Rays(r) => e.intersect16(r),
        Packet16::Recorded(raw) => e.intersect16_raw(raw, as_mitsuba),
    }
}

/// Any-hit tests of a 16-wide packet: how many of its rays are blocked (flags as in
/// `intersect16`).
fn occluded16(e: &Embree, p: &Packet16, as_mitsuba: bool) -> usize {
    match p {
        Packet16::Rays(r) => e.occluded16(r),
        Packet16::Recorded(raw) => e.occluded16_raw(raw, as_mitsuba),
    }
}

/// A scene's triangles for Embree: positions (three per triangle, unshared) and indices; and
/// the corners of the light's triangles.
struct Triangles {
    positions: Vec<[f32; 3]>,
    indices: Vec<[u32; 3]>,
    light: Vec<[Vec3; 3]>,
}

/// The scene's triangles, in primitive order.
fn triangles(scene: &Scene) -> Triangles {
    let light_shape = scene.emitters.iter().find_map(|e| match e {
        Emitter::Area(a) => Some(a.shape),
        _ => None,
    });
    let (mut pos, mut idx, mut light) = (vec![], vec![], vec![]);
    for (i, p) in scene.prims.iter().enumerate() {
        let Prim::Triangle { shape, .. } = p else {
            panic!("a primitive that is not a triangle: this bench takes triangle scenes only");
        };
        let c = scene.triangle(i).expect("a triangle");
        let n = pos.len() as u32;
        pos.extend(c.map(|v| v.to_array()));
        idx.push([n, n + 1, n + 2]);
        if Some(*shape) == light_shape {
            light.push(c);
        }
    }
    Triangles {
        positions: pos,
        indices: idx,
        light,
    }
}

/// The rays a path vertex at `si` casts: a continuation ray, uniform over the hemisphere `si` was
/// seen from, and a shadow segment to a uniform point on a uniformly chosen light triangle.
fn vertex_rays(si: &Interaction, light: &[[Vec3; 3]], rng: &mut Rng) -> (Ray, Ray) {
    let side = si.ng.dot(si.wi).signum();
    let d = rng.dir();
    let bounce = si.spawn_ray(if d.dot(si.ng) * side < 0.0 { -d } else { d });
    let [a, e1, e2] = light[(rng.f() * light.len() as f32) as usize % light.len()];
    let (mut u, mut v) = (rng.f(), rng.f());
    if u + v > 1.0 {
        (u, v) = (1.0 - u, 1.0 - v);
    }
    (bounce, si.spawn_ray_to(a + (e1 - a) * u + (e2 - a) * v))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let replay = args
        .iter()
        .position(|a| a == "--replay")
        .map(|i| args.get(i + 1).expect("--replay PREFIX").clone());
    let arg = args
        .iter()
        .enumerate()
        .find(|&(i, a)| !a.starts_with('-') && (i == 0 || args[i - 1] != "--replay"))
        .map(|(_, a)| a.clone());
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let path = arg.map_or_else(|| root.join("scenes/cbox.xml"), Into::into);
    let scene = load_scene(&path, &[])
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    let Triangles {
        positions: pos,
        indices: idx,
        light,
    } = triangles(&scene);
    assert!(!light.is_empty(), "the scene needs a triangle area light");
    let embree = Embree::new(&pos, &idx);
    let robust = Embree::with_mode(&pos, &idx, Mode::Robust);
    let mitsuba = Embree::with_mode(&pos, &idx, Mode::Mitsuba);
    let b = scene.bounds();
    let (lo, size) = (b.min, b.max - b.min);
    let mut rng = Rng(11);
    let (mut bounce, mut shadow) = (vec![], vec![]);
    while bounce.len() < 1 << 16 {
        let o = lo + size * Vec3::new(rng.f(), rng.f(), rng.f()) * 0.98 + size * 0.01;
        let Some(si) = scene.intersect(&Ray::new(o, rng.dir())) else {
            continue;
        };
        let (b, s) = vertex_rays(&si, &light, &mut rng);
        bounce.push(b);
        shadow.push(s);
    }
    // A pixel's samples at the first vertex, as a renderer whose packets hold one pixel's
    // samples casts them: 16 jittered camera rays of one pixel (pixels in random order), and from
    // each one's hit a continuation ray and a shadow segment as above.
    let (mut camera_px, mut bounce_px, mut shadow_px) = (vec![], vec![], vec![]);
    let (w, h) = (scene.camera.width, scene.camera.height);
    while camera_px.len() < 1 << 16 {
        let px = Vec2::new(
            (rng.f() * w as f32).floor().min(w as f32 - 1.0),
            (rng.f() * h as f32).floor().min(h as f32 - 1.0),
        );
        let group: Vec<Ray> = (0..16)
            .map(|_| scene.camera.generate_ray(px + Vec2::new(rng.f(), rng.f())))
            .collect();
        let hits: Vec<_> = group.iter().filter_map(|r| scene.intersect(r)).collect();
        if hits.len() < group.len() {
            continue;
        }
        for (r, si) in group.into_iter().zip(hits) {
            camera_px.push(r);
            let (b, s) = vertex_rays(&si, &light, &mut rng);
            bounce_px.push(b);
            shadow_px.push(s);
        }
    }
    println!(
        "{}: {} triangles, {} rays of each kind; M rays/s, one thread, best of 5",
        path.display(),
        idx.len(),
        bounce.len()
    );
    // The casts, in the order of the columns: Tessera, then Embree's fast mode one ray at a time
    // and in packets of 8 and 16, its robust mode one at a time, and Embree set up as Mitsuba 3 sets
    // it up (high build quality, camera packets marked coherent) one at a time and in packets of 16.
    const CASTS: [&str; 7] = [
        "tessera",
        "embree1",
        "embree8",
        "embree16",
        "embreeR1",
        "embreeM1",
        "embreeM16",
    ];
    let mut header = format!("{:>10}", "rays");
    for c in CASTS {
        header += &format!(" {c:>9}");
    }
    for c in &CASTS[1..] {
        header += &format!(" {:>8}", format!("t/{}", c.replace("embree", "e")));
    }
    println!("{header}");
    // Mitsuba's own packets, when recorded (how each column casts them: below).
    let (mut closest_mi, mut shadow_mi) = (vec![], vec![]);
    if let Some(prefix) = &replay {
        closest_mi = recorded_packets(Path::new(&format!("{prefix}.intersect")));
        shadow_mi = recorded_packets(Path::new(&format!("{prefix}.occluded")));
        let lanes = |p: &[(Vec<Ray>, RawPacket16)]| {
            p.iter().map(|(r, _)| r.len()).sum::<usize>() as f64 / p.len() as f64
        };
        println!(
            "recorded: {} closest-hit packets ({:.1} lanes each), {} any-hit packets ({:.1} lanes each)",
            closest_mi.len(),
            lanes(&closest_mi),
            shadow_mi.len(),
            lanes(&shadow_mi)
        );
    }
    let mut sets: Vec<RaySet> = vec![
        ("bounce", bounce, None, false),
        ("shadow", shadow, None, true),
        ("camera px", camera_px, None, false),
        ("bounce px", bounce_px, None, false),
        ("shadow px", shadow_px, None, true),
    ];
    if replay.is_some() {
        let rays = |p: &[(Vec<Ray>, RawPacket16)]| -> Vec<Ray> {
            p.iter().flat_map(|(r, _)| r.iter().copied()).collect()
        };
        sets.push(("mi closest", rays(&closest_mi), Some(&closest_mi), false));
        sets.push(("mi shadow", rays(&shadow_mi), Some(&shadow_mi), true));
    }
    for (kind, rays, recorded, any) in sets {
        let n = rays.len();
        // Mitsuba 3 marks its camera rays' packets coherent, no others.
        let camera = kind == "camera px";
        let singles: Vec<&[Ray]> = rays.chunks(1).collect();
        // Recorded rows: eight lanes take each recorded packet's active rays, eight at a time;
        // sixteen lanes take the packet exactly as recorded (mask and idle lanes included).
        let (p8, p16): (Vec<&[Ray]>, Vec<Packet16>) = match recorded {
            Some(p) => (
                p.iter().flat_map(|(r, _)| r.chunks(8)).collect(),
                p.iter().map(|(_, raw)| Packet16::Recorded(raw)).collect(),
            ),
            None => (
                rays.chunks(8).collect(),
                rays.chunks(16).map(Packet16::Rays).collect(),
            ),
        };
        let mut best = [0.0f64; CASTS.len()];
        let mut hits = [0usize; CASTS.len()];
        for _ in 0..5 {
            let r = if any {
                [
                    rate(&singles, n, 1, |c| usize::from(scene.occluded(&c[0]))),
                    rate(&singles, n, 1, |c| usize::from(embree.occluded(&c[0]))),
                    rate(&p8, n, 1, |c| embree.occluded8(c)),
                    rate(&p16, n, 1, |p| occluded16(&embree, p, false)),
                    rate(&singles, n, 1, |c| usize::from(robust.occluded(&c[0]))),
                    rate(&singles, n, 1, |c| usize::from(mitsuba.occluded(&c[0]))),
                    rate(&p16, n, 1, |p| occluded16(&mitsuba, p, true)),
                ]
            } else {
                [
                    rate(&singles, n, 1, |c| {
                        usize::from(scene.intersect_hit(&c[0]).is_some())
                    }),
                    rate(&singles, n, 1, |c| {
                        usize::from(embree.intersect(&c[0]).is_some())
                    }),
                    rate(&p8, n, 1, |c| embree.intersect8(c)),
                    rate(&p16, n, 1, |p| intersect16(&embree, p, false, false)),
                    rate(&singles, n, 1, |c| {
                        usize::from(robust.intersect(&c[0]).is_some())
                    }),
                    rate(&singles, n, 1, |c| {
                        usize::from(mitsuba.intersect(&c[0]).is_some())
                    }),
                    rate(&p16, n, 1, |p| intersect16(&mitsuba, p, true, camera)),
                ]
            };
            for (k, (s, h)) in r.into_iter().enumerate() {
                best[k] = best[k].max(s);
                hits[k] = h;
            }
        }
        // Rays grazing an edge may be decided differently (Tessera's test is watertight):
        // allow a few in a thousand, no more.
        for (k, h) in hits.iter().enumerate() {
            let diff = h.abs_diff(hits[0]);
            assert!(
                diff * 1000 <= rays.len() * 2,
                "{kind}: cast {k} found {h} hits, Tessera {}",
                hits[0]
            );
        }
        let mut row = format!("{kind:>10}");
        for b in best {
            row += &format!(" {:>9.2}", b / 1e6);
        }
        for b in &best[1..] {
            row += &format!(" {:>8.2}", best[0] / b);
        }
        println!("{row}   hits {hits:?}");
    }
}

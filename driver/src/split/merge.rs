//! Assembling parts into one image.
//!
//! Parts must agree on the image size, seed, integrator and scene hash. Parts are taken in order
//! of their sample range's start (then in the order given); for each pixel the first part that
//! holds it is copied, and each later one must continue its sample range exactly (its range
//! starts where the pixel's range so far ends) and is added with `PixelAccum::merge`. So:
//! - spatial parts (crop windows, tile sets) of one sample range are copied: the image is bit
//!   for bit the one a single whole render gives;
//! - sample-range parts `0..a`, `a..b`, ... of the same pixels add up to one `0..b` render within
//!   float rounding (the sums, f64 and the splatted f32 ones, are associated differently);
//! - overlapping samples, gaps in a pixel's samples, and pixels with different final ranges are
//!   errors; pixels in no part are an error unless allowed (they are then black).
use super::part::Part;
use crate::render::Framebuffer;
use std::ops::Range;

/// A merged image.
#[derive(Clone, Debug)]
pub struct Merged {
    /// The accumulators of every pixel (empty where no part holds the pixel).
    pub fb: Framebuffer,
    /// The sample range every covered pixel holds.
    pub samples: Range<u64>,
    /// Pixels no part holds.
    pub missing: usize,
}

/// Merges `parts` (each with a name for messages, e.g. its file). `allow_missing` accepts pixels
/// that no part holds. Errors are one line.
pub fn merge_parts(parts: &[(String, Part)], allow_missing: bool) -> Result<Merged, String> {
    let Some((first_name, first)) = parts.first() else {
        return Err("no parts to merge".into());
    };
    let a = &first.info;
    for (name, p) in &parts[1..] {
        let b = &p.info;
        let differs = |what: &str, x: String, y: String| {
            format!(
                "{name}: {what} {y} differs from {first_name}'s {x}; parts of one image must agree"
            )
        };
        if (a.width, a.height) != (b.width, b.height) {
            return Err(differs(
                "image size",
                format!("{}x{}", a.width, a.height),
                format!("{}x{}", b.width, b.height),
            ));
        }
        if a.seed != b.seed {
            return Err(differs("seed", a.seed.to_string(), b.seed.to_string()));
        }
        if a.scene_hash != b.scene_hash {
            return Err(differs(
                "scene hash (scene file or -D overrides)",
                format!("{:016x}", a.scene_hash),
                format!("{:016x}", b.scene_hash),
            ));
        }
        if a.integrator != b.integrator {
            return Err(differs(
                "integrator",
                a.integrator.clone(),
                b.integrator.clone(),
            ));
        }
        let reach = |p: &Part| p.splats.as_ref().map(|s| s.reach);
        if reach(first) != reach(p) {
            let say = |r: Option<u32>| r.map_or("not splatted".into(), |r| format!("reach {r}"));
            return Err(differs(
                "reconstruction (splatted samples' reach)",
                say(reach(first)),
                say(reach(p)),
            ));
        }
    }
    let (w, h) = (a.width, a.height);
    let mut order: Vec<usize> = (0..parts.len()).collect();
    order.sort_by_key(|&i| parts[i].1.info.samples.start);
    let mut fb = Framebuffer::with_reach(w, h, first.splats.as_ref().map(|s| s.reach));
    // Per pixel: the sample range so far (`end == 0` and `owner == NONE`: no part yet) and the
    // part that last added to it.
    const NONE: usize = usize::MAX;
    let mut range = vec![(0u64, 0u64); fb.pixels.len()];
    let mut owner = vec![NONE; fb.pixels.len()];
    for &i in &order {
        let (name, part) = &parts[i];
        let s = &part.info.samples;
        for r in part.info.selection.rects(w, h, part.info.tile_size) {
            for y in r.y0..r.y1 {
                for x in r.x0..r.x1 {
                    let k = y as usize * w as usize + x as usize;
                    let src = part.at(x, y);
                    let splats = fb.splats.as_mut().map(|f| f.pixel_mut(k));
                    if owner[k] == NONE {
                        fb.pixels[k] = *src;
                        if let (Some(to), Some(from)) = (splats, part.splats_at(x, y)) {
                            to.copy_from_slice(from);
                        }
                        range[k] = (s.start, s.end);
                    } else if range[k].1 == s.start {
                        fb.pixels[k].merge(src);
                        if let (Some(to), Some(from)) = (splats, part.splats_at(x, y)) {
                            to.iter_mut().zip(from).for_each(|(t, f)| *t += f);
                        }
                        range[k].1 = s.end;
                    } else if s.start < range[k].1 {
                        return Err(format!(
                            "{name} and {} overlap: both hold samples {}..{} of pixel ({x}, {y})",
                            parts[owner[k]].0,
                            s.start,
                            s.end.min(range[k].1)
                        ));
                    } else {
                        return Err(format!(
                            "pixel ({x}, {y}) has samples {}..{} and then {}..{} (from {name}): \
                             samples {}..{} are in no part",
                            range[k].0, range[k].1, s.start, s.end, range[k].1, s.start
                        ));
                    }
                    owner[k] = i;
                }
            }
        }
    }
    let mut missing = 0usize;
    let mut first_missing = None;
    let mut common: Option<(usize, (u64, u64))> = None;
    for k in 0..fb.pixels.len() {
        if owner[k] == NONE {
            missing += 1;
            first_missing.get_or_insert(k);
            continue;
        }
        match common {
            None => common = Some((k, range[k])),
            Some((j, r)) if r != range[k] => {
                let at = |k: usize| format!("({}, {})", k % w as usize, k / w as usize);
                return Err(format!(
                    "pixel {} has samples {}..{} but pixel {} has {}..{}: the parts do not give \
                     every pixel the same samples",
                    at(j),
                    r.0,
                    r.1,
                    at(k),
                    range[k].0,
                    range[k].1
                ));
            }
            _ => {}
        }
    }
    if missing > 0 && !allow_missing {
        let k = first_missing.unwrap_or(0);
        return Err(format!(
            "{missing} of {} pixels are in no part (the first is ({}, {})); add the missing \
             parts or pass --allow-missing to leave them black",
            fb.pixels.len(),
            k % w as usize,
            k / w as usize
        ));
    }
    let samples = common.map_or(0..0, |(_, r)| r.0..r.1);
    Ok(Merged {
        fb,
        samples,
        missing,
    })
}

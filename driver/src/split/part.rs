//! Part files: one piece of a split render, as an OpenEXR file that viewers can open.
//!
//! The display window is the whole image; the data window is the bounding box of the part's
//! pixels (pixels of the box outside the selection, e.g. other tile sets, are empty: black).
//! Channels (single layer, sorted by name as EXR requires):
//! - `R`, `G`, `B` (f32): each pixel's mean, for viewing;
//! - `tessera.{sum,sumsq}.{R,G,B}.{hi,lo}` (u32): the high and low 32 bits of each f64 sum of
//!   sample values and squared values, so the sums are stored exactly;
//! - `tessera.{count,dropped,rays}.{hi,lo}` (u32): the 64-bit counts of accepted and dropped
//!   samples and of the rays they cast (what adaptive sampling prices a pixel's samples by);
//! - when the render splats its samples, `tessera.splat.NNN` (f32, `NNN` from `000`): each
//!   pixel's splatted sums (`driver/src/splats.rs`), one channel per float, stored exactly.
//!
//! Text attributes: `tessera.part` (format version, `2`; version 1, without the ray counts, is
//! still read), `tessera.size` (`WxH`),
//! `tessera.pixels` (`all`, `crop X0,Y0,X1,Y1` or `tiles K/N`), `tessera.tileSize`,
//! `tessera.samples` (`a..b`), `tessera.seed`, `tessera.integrator`, `tessera.sceneHash` (16 hex
//! digits, [`tessera_scene::hash::scene_hash`]). A file without `tessera.part` is not a part.
use super::selection::PixelSelection;
use crate::image_io::write_atomic;
use crate::render::{Framebuffer, Tile};
use crate::splats::Splats;
use exr::prelude::{
    AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Layer, LayerAttributes,
    ReadChannels, ReadLayers, SampleType, SmallVec, Text, Vec2,
};
use std::ops::Range;
use std::path::Path;
use tessera_core::film::PixelAccum;
use tessera_core::splat::{stride, MAX_REACH};

/// What a part is a part of, and which piece it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PartInfo {
    /// Width of the whole image.
    pub width: u32,
    /// Height of the whole image.
    pub height: u32,
    /// The pixels the part holds.
    pub selection: PixelSelection,
    /// Tile size the selection's tile sets refer to.
    pub tile_size: u32,
    /// The sample indices rendered.
    pub samples: Range<u64>,
    /// Seed of every random stream.
    pub seed: u64,
    /// The integrator and its parameters (as text; parts to merge must agree exactly).
    pub integrator: String,
    /// [`tessera_scene::hash::scene_hash`] of the scene file and its `-D` overrides.
    pub scene_hash: u64,
}

/// A part read back: its settings and the accumulators of its bounding box.
#[derive(Clone, Debug)]
pub struct Part {
    /// Settings.
    pub info: PartInfo,
    /// Bounding box of the selection (the EXR data window).
    pub window: Tile,
    /// Accumulators of the window, row-major.
    pub pixels: Vec<PixelAccum>,
    /// When the render splats: the reach, and the window's splatted sums, row-major.
    pub splats: Option<Splats>,
}

impl Part {
    /// The accumulator of image pixel `(x, y)`, which must lie in the window.
    pub fn at(&self, x: u32, y: u32) -> &PixelAccum {
        &self.pixels[self.index(x, y)]
    }

    /// The splatted sums of image pixel `(x, y)`, which must lie in the window.
    pub fn splats_at(&self, x: u32, y: u32) -> Option<&[f32]> {
        self.splats.as_ref().map(|s| s.pixel(self.index(x, y)))
    }

    fn index(&self, x: u32, y: u32) -> usize {
        let w = (self.window.x1 - self.window.x0) as usize;
        (y - self.window.y0) as usize * w + (x - self.window.x0) as usize
    }
}

/// Name of splatted-sum channel `i`.
fn splat_channel(i: usize) -> String {
    format!("tessera.splat.{i:03}")
}

const VERSION: &str = "2";

/// The exact-data channel names (two per word of [`PixelAccum::to_words`], high half first).
fn word_channels() -> Vec<String> {
    let mut v = Vec::with_capacity(2 * PixelAccum::WORDS);
    for q in ["sum", "sumsq"] {
        for c in ["R", "G", "B"] {
            for h in ["hi", "lo"] {
                v.push(format!("tessera.{q}.{c}.{h}"));
            }
        }
    }
    for q in ["count", "dropped", "rays"] {
        for h in ["hi", "lo"] {
            v.push(format!("tessera.{q}.{h}"));
        }
    }
    v
}

fn text(s: &str) -> Result<Text, String> {
    Text::new_or_none(s).ok_or_else(|| format!("cannot store \"{s}\" in an EXR attribute"))
}

/// Writes the selected pixels of `fb` (the whole image's framebuffer) as a part, atomically.
pub fn write_part(path: &Path, info: &PartInfo, fb: &Framebuffer) -> Result<(), String> {
    write_version(path, info, fb, VERSION, PixelAccum::WORDS)
}

/// [`write_part`] as format `version`, whose pixels hold the first `words` words of
/// [`PixelAccum::to_words`].
fn write_version(
    path: &Path,
    info: &PartInfo,
    fb: &Framebuffer,
    version: &str,
    words: usize,
) -> Result<(), String> {
    let err = |e: String| format!("{}: cannot write part: {e}", path.display());
    if (fb.width, fb.height) != (info.width, info.height) {
        return Err(err(format!(
            "the framebuffer is {}x{}, the part says {}x{}",
            fb.width, fb.height, info.width, info.height
        )));
    }
    let win = info
        .selection
        .bounds(info.width, info.height, info.tile_size)
        .ok_or_else(|| err("the selection holds no pixel".into()))?;
    let n = ((win.x1 - win.x0) * (win.y1 - win.y0)) as usize;
    let image = fb.rgb();
    let stride = fb.splats.as_ref().map_or(0, Splats::stride);
    let mut rgb: [Vec<f32>; 3] = Default::default();
    let mut halves: Vec<Vec<u32>> = (0..2 * PixelAccum::WORDS)
        .map(|_| Vec::with_capacity(n))
        .collect();
    let mut splat: Vec<Vec<f32>> = (0..stride).map(|_| Vec::with_capacity(n)).collect();
    for y in win.y0..win.y1 {
        for x in win.x0..win.x1 {
            let i = y as usize * info.width as usize + x as usize;
            let p = &fb.pixels[i];
            for (c, m) in rgb.iter_mut().zip(image[i]) {
                c.push(m);
            }
            for (i, w) in p.to_words().into_iter().enumerate() {
                halves[2 * i].push((w >> 32) as u32);
                halves[2 * i + 1].push(w as u32);
            }
            if let Some(s) = &fb.splats {
                for (c, &v) in splat.iter_mut().zip(s.pixel(i)) {
                    c.push(v);
                }
            }
        }
    }
    let mut list = Vec::with_capacity(3 + 2 * PixelAccum::WORDS + stride);
    for (name, data) in ["R", "G", "B"].into_iter().zip(rgb) {
        list.push(AnyChannel::new(name, FlatSamples::F32(data)));
    }
    for (name, data) in word_channels().into_iter().zip(halves).take(2 * words) {
        list.push(AnyChannel::new(text(&name)?, FlatSamples::U32(data)));
    }
    for (i, data) in splat.into_iter().enumerate() {
        list.push(AnyChannel::new(
            text(&splat_channel(i))?,
            FlatSamples::F32(data),
        ));
    }
    let mut attrs = LayerAttributes {
        layer_position: Vec2(win.x0 as i32, win.y0 as i32),
        ..LayerAttributes::default()
    };
    let fields = [
        ("tessera.part", version.to_string()),
        ("tessera.size", format!("{}x{}", info.width, info.height)),
        ("tessera.pixels", info.selection.to_string()),
        ("tessera.tileSize", info.tile_size.to_string()),
        (
            "tessera.samples",
            format!("{}..{}", info.samples.start, info.samples.end),
        ),
        ("tessera.seed", info.seed.to_string()),
        ("tessera.integrator", info.integrator.clone()),
        ("tessera.sceneHash", format!("{:016x}", info.scene_hash)),
    ];
    for (k, v) in fields {
        attrs
            .other
            .insert(text(k)?, AttributeValue::Text(text(&v).map_err(err)?));
    }
    let layer = Layer::new(
        Vec2((win.x1 - win.x0) as usize, (win.y1 - win.y0) as usize),
        attrs,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(list)),
    );
    let mut image = exr::image::Image::from_layer(layer);
    image.attributes.display_window = exr::prelude::IntegerBounds::new(
        Vec2(0, 0),
        Vec2(info.width as usize, info.height as usize),
    );
    // Compressed on every core: a part holds a float channel per splat sum.
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    write_atomic(path, |tmp| {
        crate::exr_blocks::write_parallel(&image, tmp, threads)
    })
    .map_err(err)
}

/// The text attribute `name` of a header.
fn attr(
    other: &std::collections::HashMap<Text, AttributeValue>,
    name: &str,
) -> Result<String, String> {
    match other.get(&Text::from(name)) {
        Some(AttributeValue::Text(t)) => Ok(t.to_string()),
        Some(_) => Err(format!("attribute {name} is not text")),
        None => Err(format!("attribute {name} is missing")),
    }
}

fn parse<T: std::str::FromStr>(s: &str, what: &str) -> Result<T, String> {
    s.trim().parse().map_err(|_| format!("bad {what} \"{s}\""))
}

/// Reads and checks a part file. Errors are one line, naming the file.
pub fn read_part(path: &Path) -> Result<Part, String> {
    let err = |e: String| format!("{}: {e}", path.display());
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| err(format!("cannot read EXR header: {e}")))?;
    let [header] = meta.headers.as_slice() else {
        return Err(err("not a Tessera part (expected one EXR layer)".into()));
    };
    let other = &header.own_attributes.other;
    let version = attr(other, "tessera.part").map_err(|_| {
        err("not a Tessera part (no tessera.part attribute; render with --crop, --tiles or --sample-range to an .exr)".into())
    })?;
    // Version 1 parts hold no ray counts (read as 0).
    let words = match version.as_str() {
        VERSION => PixelAccum::WORDS,
        "1" => PixelAccum::WORDS - 1,
        _ => return Err(err(format!("unsupported part version {version}"))),
    };
    let info = part_info(other).map_err(err)?;
    let win = info
        .selection
        .check(info.width, info.height, info.tile_size)
        .and_then(|_| {
            info.selection
                .bounds(info.width, info.height, info.tile_size)
                .ok_or_else(|| "the selection holds no pixel".to_string())
        })
        .map_err(err)?;
    let display = header.shared_attributes.display_window;
    let data_pos = header.own_attributes.layer_position;
    if header.deep
        || display.position != Vec2(0, 0)
        || display.size != Vec2(info.width as usize, info.height as usize)
        || data_pos != Vec2(win.x0 as i32, win.y0 as i32)
        || header.layer_size != Vec2((win.x1 - win.x0) as usize, (win.y1 - win.y0) as usize)
    {
        return Err(err(format!(
            "the EXR windows do not match the part's settings ({} of {}x{})",
            info.selection, info.width, info.height
        )));
    }
    let mut names = word_channels();
    names.truncate(2 * words);
    for name in &names {
        let found = header
            .channels
            .list
            .iter()
            .find(|c| c.name == *name.as_str());
        match found {
            Some(c) if c.sample_type == SampleType::U32 => {}
            _ => return Err(err(format!("channel {name} (u32) is missing"))),
        }
    }
    let image = read_pixels(path).map_err(err)?;
    let layer = &image.layer_data;
    let n = layer.size.0 * layer.size.1;
    let mut cols: Vec<&[u32]> = Vec::with_capacity(2 * PixelAccum::WORDS);
    for name in &names {
        let ch = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name.as_str());
        match ch.map(|c| &c.sample_data) {
            Some(FlatSamples::U32(v)) if v.len() == n => cols.push(v),
            _ => return Err(err(format!("channel {name} is not {n} u32 samples"))),
        }
    }
    let pixels: Vec<PixelAccum> = (0..n)
        .map(|i| {
            PixelAccum::from_words(std::array::from_fn(|k| {
                if k < words {
                    (cols[2 * k][i] as u64) << 32 | cols[2 * k + 1][i] as u64
                } else {
                    0
                }
            }))
        })
        .collect();
    let finite = |p: &PixelAccum| p.sum.iter().chain(&p.sum_sq).all(|v| v.is_finite());
    if !pixels.iter().all(finite) {
        return Err(err("a pixel's sums are not finite".into()));
    }
    let splats = read_splats(layer, n).map_err(err)?;
    Ok(Part {
        info,
        window: win,
        pixels,
        splats,
    })
}

type FlatImage = exr::image::Image<exr::image::Layer<AnyChannels<FlatSamples>>>;

/// The splatted sums of a part's `n` pixels, if it has any: `tessera.splat.000` onwards, as many
/// channels as a footprint of some reach keeps, each `n` finite f32 samples.
fn read_splats(
    layer: &exr::image::Layer<AnyChannels<FlatSamples>>,
    n: usize,
) -> Result<Option<Splats>, String> {
    let list = &layer.channel_data.list;
    let count = list
        .iter()
        .filter(|c| c.name.to_string().starts_with("tessera.splat."))
        .count();
    if count == 0 {
        return Ok(None);
    }
    let reach = (0..=MAX_REACH)
        .find(|&r| stride(r) == count)
        .ok_or_else(|| format!("{count} splatted-sum channels, which no footprint keeps"))?;
    let mut splats = Splats::new(reach, n);
    for i in 0..count {
        let name = splat_channel(i);
        let data = match list.iter().find(|c| c.name == *name.as_str()) {
            Some(c) => &c.sample_data,
            None => return Err(format!("channel {name} is missing")),
        };
        match data {
            FlatSamples::F32(v) if v.len() == n && v.iter().all(|x| x.is_finite()) => {
                for (k, &x) in v.iter().enumerate() {
                    splats.pixel_mut(k)[i] = x;
                }
            }
            _ => return Err(format!("channel {name} is not {n} finite f32 samples")),
        }
    }
    Ok(Some(splats))
}

/// Decodes every channel of the file's one layer. The decoder is not trusted to reject every
/// malformed file without panicking, so a panic is caught and reported as an error.
fn read_pixels(path: &Path) -> Result<FlatImage, String> {
    let read = || {
        exr::prelude::read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .from_file(path)
    };
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(read);
    std::panic::set_hook(hook);
    match result {
        Ok(Ok(img)) => Ok(img),
        Ok(Err(e)) => Err(format!("cannot decode EXR: {e}")),
        Err(_) => Err("cannot decode EXR: malformed file".into()),
    }
}

fn part_info(other: &std::collections::HashMap<Text, AttributeValue>) -> Result<PartInfo, String> {
    let size = attr(other, "tessera.size")?;
    let (w, h) = size
        .split_once('x')
        .ok_or_else(|| format!("bad size \"{size}\""))?;
    let samples = attr(other, "tessera.samples")?;
    let samples = super::selection::parse_sample_range(&samples)?;
    let hash = attr(other, "tessera.sceneHash")?;
    let info = PartInfo {
        width: parse(w, "width")?,
        height: parse(h, "height")?,
        selection: PixelSelection::parse(&attr(other, "tessera.pixels")?)?,
        tile_size: parse(&attr(other, "tessera.tileSize")?, "tile size")?,
        samples,
        seed: parse(&attr(other, "tessera.seed")?, "seed")?,
        integrator: attr(other, "tessera.integrator")?,
        scene_hash: u64::from_str_radix(hash.trim(), 16)
            .map_err(|_| format!("bad scene hash \"{hash}\""))?,
    };
    // Bounds that keep the tile list and the pixel buffers of a malformed header small enough
    // to compute (the renderer's own limits are far inside them).
    let (w, h, ts) = (info.width as u64, info.height as u64, info.tile_size as u64);
    if w == 0 || h == 0 || w * h > 1 << 30 || !(1..=4096).contains(&ts) {
        return Err(format!(
            "bad image size {w}x{h} or tile size {ts} (1..=4096)"
        ));
    }
    if w.div_ceil(ts) * h.div_ceil(ts) > 1 << 24 {
        return Err(format!("too many tiles: {w}x{h} in tiles of {ts} px"));
    }
    Ok(info)
}

#[cfg(test)]
mod tests;

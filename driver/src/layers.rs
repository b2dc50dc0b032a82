//! The extra image channels of `aov` and `moment` integrators ([`tessera_scene::Layer`]) and the
//! multichannel EXR they are written to.
//!
//! Each layer (up to three channels) is an ordinary render of its own integrator with the
//! colour render's scene, seed, sampler and sample range: every pixel draws the same camera
//! samples (the filter offset and the lens position come first from the sampler), each sample's
//! value is weighted by the reconstruction filter exactly as the colour is (importance-sampled
//! offsets, plus the signed weight of filters with negative lobes), and pixel means are taken
//! the same way. So a channel is the filter-weighted average of its variable over the pixel's
//! samples, which is what Mitsuba 3's film computes, and the bits do not depend on the thread
//! count or the tile size. A layer whose integrator is the colour's own is not rendered again
//! but taken from the colour ([`render_layers`]): the colour itself, its XYZ, or the XYZ
//! squares its pass gathered beside it ([`Framebuffer::squares`]). Surface variables are
//! gathered in the colour's pass too when it was asked to ([`Framebuffer::aovs`]: one more
//! cast of each camera ray for all of them), with the same bits. Only further nested
//! integrators (and surface variables beside a colour that reuses paths) take a render each;
//! Mitsuba computes every channel in the colour's pass.
use crate::image_io::write_atomic;
use crate::render::{render, Framebuffer, RenderOptions};
use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, Layer as ExrLayer};
use exr::prelude::{LayerAttributes, ReadChannels, ReadLayers, SmallVec, Vec2};
use std::ops::Range;
use std::path::Path;
use tessera_core::glam::Vec3;
use tessera_core::integrator::{AovIntegrator, Integrator, SRGB_TO_XYZ};
use tessera_core::render::RenderJob;
use tessera_core::scene::Scene;
use tessera_scene::{Layer, LayerSource};

/// One image channel: its name and its values, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// The channel name (Mitsuba 3's, e.g. `nn.X`).
    pub name: String,
    /// One value per pixel, row-major.
    pub values: Vec<f32>,
}

/// Renders every layer with samples `samples` of each pixel from `seed`; the channels in the
/// layers' order. `colour` is the colour image's pixel means from the same samples, and
/// `gathered` the colour's framebuffer, if what its pass gathered beside the colour should be
/// used ([`Framebuffer::squares`], [`Framebuffer::aovs`]): a layer whose integrator is the
/// colour's ([`Layer::colour`]) is taken from them rather than rendered again, as it is (`aov`:
/// the same bits a render would give), converted to XYZ (a first moment: the mean of the
/// converted samples up to rounding, as the conversion is linear), or the squares' means (a
/// second moment: the bits a render would give); a surface variable gathered with this sample
/// count is its gathered sums' means (the bits its render would give).
pub fn render_layers(
    scene: &Scene,
    layers: &[Layer],
    seed: u64,
    samples: Range<u64>,
    opts: &RenderOptions,
    colour: &[[f32; 3]],
    gathered: Option<&Framebuffer>,
) -> Result<Vec<Channel>, String> {
    let mut out = Vec::new();
    let squares = gathered.and_then(|g| g.squares.as_deref());
    let aovs = gathered.map_or(&[][..], |g| &g.aovs[..]);
    for layer in layers {
        let from_colour = match (&layer.source, layer.colour, squares) {
            (LayerSource::Aov(a), _, _) => aovs
                .iter()
                .find(|g| g.aov.aov == *a && g.aov.spp == samples.end)
                .map(|g| g.fb.rgb()),
            (LayerSource::Nested(_), true, _) => Some(colour.to_vec()),
            (LayerSource::Moment { square: false, .. }, true, _) => Some(
                colour
                    .iter()
                    .map(|c| (SRGB_TO_XYZ * Vec3::from(*c)).to_array())
                    .collect(),
            ),
            (LayerSource::Moment { square: true, .. }, true, Some(q)) => Some(q.rgb()),
            _ => None,
        };
        let means = match from_colour {
            Some(m) => m,
            None => render_layer(scene, layer, seed, samples.clone(), opts)?.rgb(),
        };
        for (c, name) in layer.names.iter().enumerate().take(3) {
            out.push(Channel {
                name: name.clone(),
                values: means.iter().map(|m| m[c]).collect(),
            });
        }
    }
    Ok(out)
}

/// Whether a colour render for `layers` should gather its samples' XYZ squares
/// ([`Framebuffer::with_squares`]): a second moment of the colour's own integrator is among
/// them.
pub fn wants_squares(layers: &[Layer]) -> bool {
    layers
        .iter()
        .any(|l| l.colour && matches!(l.source, LayerSource::Moment { square: true, .. }))
}

/// The surface variables among `layers` ([`LayerSource::Aov`]) as a colour render of `spp`
/// samples a pixel gathers them ([`Framebuffer::with_aovs`]).
pub fn gathered_aovs(layers: &[Layer], spp: u64) -> Vec<AovIntegrator> {
    layers
        .iter()
        .filter_map(|l| match l.source {
            LayerSource::Aov(a) => Some(AovIntegrator::new(a, spp)),
            _ => None,
        })
        .collect()
}

/// Renders one layer (its channels are the first of each pixel's colour sums).
pub fn render_layer(
    scene: &Scene,
    layer: &Layer,
    seed: u64,
    samples: Range<u64>,
    opts: &RenderOptions,
) -> Result<Framebuffer, String> {
    let mut integrator = layer
        .build()
        .ok_or_else(|| format!("cannot build the integrator of channels {:?}", layer.names))?;
    if let Integrator::Aov(a) = &mut integrator {
        // Mitsuba shortens the camera ray's differentials by the render's sample count.
        a.spp = samples.end;
    }
    let job = RenderJob::new(scene, &integrator, seed);
    Ok(render(&job, samples, opts, &mut |_, _| {}))
}

/// The colour image's `R`, `G`, `B` channels from its pixel means.
pub fn rgb_channels(rgb: &[[f32; 3]]) -> Vec<Channel> {
    ["R", "G", "B"]
        .iter()
        .enumerate()
        .map(|(c, n)| Channel {
            name: n.to_string(),
            values: rgb.iter().map(|p| p[c]).collect(),
        })
        .collect()
}

/// Writes `channels` (each `width * height` values) as one float EXR layer, atomically, its
/// blocks compressed on up to `threads` threads (the bytes do not depend on how many); the
/// channels are stored sorted by name, as EXR requires.
pub fn write_channels_exr(
    path: &Path,
    width: u32,
    height: u32,
    channels: &[Channel],
    threads: usize,
) -> Result<(), String> {
    let err = |e: String| format!("{}: cannot write image: {e}", path.display());
    let n = width as usize * height as usize;
    let mut list = Vec::with_capacity(channels.len());
    for c in channels {
        if c.values.len() != n {
            return Err(err(format!("channel {} has the wrong size", c.name)));
        }
        let name = exr::prelude::Text::new_or_none(&c.name)
            .ok_or_else(|| err(format!("cannot store the channel name \"{}\"", c.name)))?;
        list.push(AnyChannel::new(name, FlatSamples::F32(c.values.clone())));
    }
    let layer = ExrLayer::new(
        Vec2(width as usize, height as usize),
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(list)),
    );
    let image = exr::image::Image::from_layer(layer);
    write_atomic(path, |tmp| {
        crate::exr_blocks::write_parallel(&image, tmp, threads)
    })
    .map_err(err)
}

/// Reads every float channel of an EXR file's first layer: width, height and the channels in
/// the file's order (sorted by name). Errors are one line naming the file.
pub fn read_channels_exr(path: &Path) -> Result<(u32, u32, Vec<Channel>), String> {
    let err = |e: String| format!("{}: cannot read image: {e}", path.display());
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| err(e.to_string()))?;
    let layer = &image.layer_data;
    let (w, h) = (layer.size.0 as u32, layer.size.1 as u32);
    let channels = layer
        .channel_data
        .list
        .iter()
        .map(|c| Channel {
            name: c.name.to_string(),
            values: c.sample_data.values_as_f32().collect(),
        })
        .collect();
    Ok((w, h, channels))
}

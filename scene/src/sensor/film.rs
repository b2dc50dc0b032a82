//! The `<film>` plugins ([`FILMS`]) and what a sensor carries besides its projection: the
//! film's size, the `<rfilter>` and the `<sampler>` (Nori puts width/height on the camera).
use crate::filter::build_filter;
use crate::plugin::{self, Default, Param, ParamType, Plugin, Range};
use crate::sampler::build_sampler;
use crate::util::Result;
use crate::xml::{Kind, Object};
use tessera_core::camera::{Filter, GaussianFilter};
use tessera_core::sampling::SamplerKind;

/// Largest image edge accepted.
pub const MAX_EDGE: i64 = 1 << 16;
/// Largest pixel count accepted (the accumulation buffer takes 64 bytes a pixel).
pub const MAX_PIXELS: i64 = 1 << 26;

/// A film: its size and crop window.
pub(crate) type FilmPlugin = Plugin<fn(&Object) -> Result<FilmSize>>;

/// The size a film gives the image: the whole film's, and the window of it that is rendered
/// (`[x, y, width, height]`, pixels), if not all of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct FilmSize {
    pub width: u32,
    pub height: u32,
    pub crop: Option<[u32; 4]>,
}

/// Every `<film type=...>` Tessera knows.
pub static FILMS: &[FilmPlugin] = &[HDRFILM];

pub(super) const EDGE: Range = Range::Note("between 1 and 65536");

const WIDTH: Param = Param::integer("width", 768, EDGE, "image width in pixels");
const HEIGHT: Param = Param::integer("height", 576, EDGE, "image height in pixels");
const PIXEL_FORMAT: Param = Param::new(
    "pixel_format",
    ParamType::String,
    Default::Str("rgb"),
    Range::Any,
    "has no effect: the output is linear RGB",
)
.ignored();
const COMPONENT_FORMAT: Param = Param::new(
    "component_format",
    ParamType::String,
    Default::Str("float16"),
    Range::Any,
    "has no effect: the output file's format decides",
)
.ignored();
const FILE_FORMAT: Param = Param::new(
    "file_format",
    ParamType::String,
    Default::Str("openexr"),
    Range::Any,
    "has no effect: the output file's extension decides",
)
.ignored();

const BANNER: Param = Param::boolean(
    "banner",
    true,
    "has no effect: a Mitsuba 0.x parameter that Mitsuba 3 also ignores",
)
.ignored();
const SAMPLE_BORDER: Param = Param::boolean(
    "sample_border",
    false,
    "has no effect: samples never reach past the image's pixels",
)
.ignored();

const CROP_OFFSET_X: Param = Param::integer(
    "crop_offset_x",
    0,
    Range::Note("0 or more; the window must lie on the film"),
    "left edge of the rendered window, in pixels of the film",
);
const CROP_OFFSET_Y: Param = Param::integer(
    "crop_offset_y",
    0,
    Range::Note("0 or more; the window must lie on the film"),
    "top edge of the rendered window, in pixels of the film",
);
const CROP_WIDTH: Param = Param::new(
    "crop_width",
    ParamType::Integer,
    Default::Note("width"),
    Range::Note("1 or more; the window must lie on the film"),
    "width of the rendered window: the output image's width",
);
const CROP_HEIGHT: Param = Param::new(
    "crop_height",
    ParamType::Integer,
    Default::Note("height"),
    Range::Note("1 or more; the window must lie on the film"),
    "height of the rendered window: the output image's height",
);

/// `hdrfilm`.
pub(crate) const HDRFILM: FilmPlugin = Plugin {
    name: "hdrfilm",
    aliases: &[],
    doc: "The image's size (the outputs' formats come from their file names).",
    params: &[
        WIDTH,
        HEIGHT,
        CROP_OFFSET_X,
        CROP_OFFSET_Y,
        CROP_WIDTH,
        CROP_HEIGHT,
        PIXEL_FORMAT,
        COMPONENT_FORMAT,
        FILE_FORMAT,
        BANNER,
        SAMPLE_BORDER,
    ],
    nested: "an optional `<rfilter>`",
    build: |film| {
        let width = edge(film, &WIDTH)?;
        let height = edge(film, &HEIGHT)?;
        for p in [PIXEL_FORMAT, COMPONENT_FORMAT, FILE_FORMAT] {
            film.string_opt(p.name)?;
        }
        for p in [BANNER, SAMPLE_BORDER] {
            p.read_bool(film)?;
        }
        Ok(FilmSize {
            width,
            height,
            crop: read_crop(film, width, height)?,
        })
    },
};

/// The crop window, checked to lie on the `width` x `height` film as Mitsuba 3 checks it
/// (`None` when it is the whole film).
fn read_crop(film: &Object, width: u32, height: u32) -> Result<Option<[u32; 4]>> {
    let read = |p: &Param, default: u32, low: i64| {
        p.read_i64_or(film, default.into(), |v| (low..=MAX_EDGE).contains(&v))
            .map(|v| v as u32)
    };
    let x = read(&CROP_OFFSET_X, 0, 0)?;
    let y = read(&CROP_OFFSET_Y, 0, 0)?;
    let w = read(&CROP_WIDTH, width.saturating_sub(x), 1)?;
    let h = read(&CROP_HEIGHT, height.saturating_sub(y), 1)?;
    if w == 0 || h == 0 || x + w > width || y + h > height {
        return Err(film.error(format!(
            "the crop window {w}x{h} at ({x}, {y}) does not lie on the {width}x{height} film"
        )));
    }
    Ok(((x, y, w, h) != (0, 0, width, height)).then_some([x, y, w, h]))
}

/// An image edge read from `p`, within [`MAX_EDGE`].
pub(super) fn edge(obj: &Object, p: &Param) -> Result<u32> {
    Ok(p.read_i64_where(obj, |v| (1..=MAX_EDGE).contains(&v))? as u32)
}

/// What a sensor's children (and a Nori camera's own width/height) say.
#[derive(Debug)]
pub(super) struct Film {
    pub width: u32,
    pub height: u32,
    /// The rendered window `[x, y, width, height]` of the film, if not all of it.
    pub crop: Option<[u32; 4]>,
    pub filter: Filter,
    pub spp: Option<u64>,
    pub seed: Option<u64>,
    pub sampler: Option<SamplerKind>,
}

/// Reads the `<film>`, `<rfilter>` and `<sampler>` under sensor `obj`; `size` is the image
/// size when no film gives one.
pub(super) fn read_film(
    obj: &Object,
    size: (u32, u32),
    warnings: &mut Vec<String>,
) -> Result<Film> {
    let mut filter = Filter::Gaussian(GaussianFilter::new(0.5));
    let (mut width, mut height) = size;
    let mut crop = None;
    let (mut spp, mut seed, mut sampler) = (None, None, None);
    for c in &obj.children {
        match c.obj.kind {
            Kind::Film => {
                c.mark_used();
                let film = &c.obj;
                let plugin = plugin::find(FILMS, "film", film)?;
                let size = (plugin.build)(film)?;
                (width, height, crop) = (size.width, size.height, size.crop);
                for f in &film.children {
                    if f.obj.kind == Kind::RFilter {
                        f.mark_used();
                        filter = build_filter(&f.obj)?;
                    }
                }
                plugin.check_unused(film)?;
            }
            Kind::RFilter => {
                c.mark_used();
                filter = build_filter(&c.obj)?;
            }
            Kind::Sampler => {
                c.mark_used();
                let (n, s, k) = build_sampler(&c.obj, warnings)?;
                spp = Some(n);
                seed = Some(s);
                sampler = Some(k);
            }
            _ => {}
        }
    }
    if width as i64 * height as i64 > MAX_PIXELS {
        return Err(obj.error(format!(
            "image of {width}x{height} pixels is over the limit of {MAX_PIXELS} pixels"
        )));
    }
    Ok(Film {
        width,
        height,
        crop,
        filter,
        spp,
        seed,
        sampler,
    })
}

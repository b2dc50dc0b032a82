//! The `<sensor>` plugins ([`SENSORS`], Nori's `<camera>`) and the `<film>` plugins ([`FILMS`])
//! they carry, with the `<rfilter>` and `<sampler>` that may hang off them.
use crate::filter::build_filter;
use crate::plugin::{self, Default, Param, ParamType, Plugin, Range};
use crate::sampler::build_sampler;
use crate::util::{at_prop, Result};
use crate::xml::{Kind, Object};
use tessera_core::camera::{Filter, FovAxis, GaussianFilter, Perspective};
use tessera_core::sampling::SamplerKind;

/// Largest image edge accepted.
pub const MAX_EDGE: i64 = 1 << 16;
/// Largest pixel count accepted (the accumulation buffer takes 64 bytes a pixel).
pub const MAX_PIXELS: i64 = 1 << 26;

/// The sensor and what hangs off it.
#[derive(Debug)]
pub struct SensorParts {
    pub camera: Perspective,
    pub filter: Filter,
    pub spp: Option<u64>,
    pub seed: Option<u64>,
    pub sampler: Option<SamplerKind>,
}

/// A sensor plugin; the builder may add warnings (from its sampler).
pub type SensorPlugin = Plugin<fn(&Object, &mut Vec<String>) -> Result<SensorParts>>;

/// Every `<sensor type=...>` Tessera knows.
pub static SENSORS: &[SensorPlugin] = &[PERSPECTIVE];

/// Builds the sensor and reports unused parameters.
pub fn build_sensor(obj: &Object, warnings: &mut Vec<String>) -> Result<SensorParts> {
    let plugin = plugin::find(SENSORS, "sensor", obj)?;
    let s = (plugin.build)(obj, warnings)?;
    plugin.check_unused(obj)?;
    Ok(s)
}

/// A film: its size.
pub type FilmPlugin = Plugin<fn(&Object) -> Result<(u32, u32)>>;

/// Every `<film type=...>` Tessera knows.
pub static FILMS: &[FilmPlugin] = &[HDRFILM];

const EDGE: Range = Range::Note("between 1 and 65536");

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

/// `hdrfilm`.
pub const HDRFILM: FilmPlugin = Plugin {
    name: "hdrfilm",
    aliases: &[],
    doc: "The image's size (the outputs' formats come from their file names).",
    params: &[WIDTH, HEIGHT, PIXEL_FORMAT, COMPONENT_FORMAT, FILE_FORMAT],
    nested: "an optional `<rfilter>`",
    build: |film| {
        let width = edge(film, &WIDTH)?;
        let height = edge(film, &HEIGHT)?;
        for p in [PIXEL_FORMAT, COMPONENT_FORMAT, FILE_FORMAT] {
            film.string_opt(p.name)?;
        }
        Ok((width, height))
    },
};

fn edge(obj: &Object, p: &Param) -> Result<u32> {
    Ok(p.read_i64_where(obj, |v| (1..=MAX_EDGE).contains(&v))? as u32)
}

const TO_WORLD: Param = Param::transform(
    "to_world",
    "camera to world; the camera looks down its local +z, with +y up",
);
const NEAR_CLIP: Param = Param::new(
    "near_clip",
    ParamType::Float,
    Default::Note("0.01; 1e-4 on a Nori camera (one that carries width/height)"),
    Range::NonNegative,
    "distance before which nothing is seen",
);
const FAR_CLIP: Param = Param::new(
    "far_clip",
    ParamType::Float,
    Default::Float(10000.0),
    Range::Note("greater than near_clip"),
    "distance beyond which nothing is seen",
);
const FOV: Param = Param::new(
    "fov",
    ParamType::Float,
    Default::Absent,
    Range::open(0.0, 180.0),
    "field of view along fov_axis (else focal_length sets it)",
)
.with_unit("degrees");
const FOV_AXIS: Param = Param::choice(
    "fov_axis",
    "x",
    &["x", "y", "diagonal", "smaller", "larger"],
    "the image axis fov spans",
);
const FOCAL_LENGTH: Param = Param::new(
    "focal_length",
    ParamType::String,
    Default::Str("50mm"),
    Range::Note("a positive length like \"50mm\""),
    "focal length on a 36x24 mm frame (a diagonal field of view), when fov is absent",
);
const FOCUS_DISTANCE: Param = Param::new(
    "focus_distance",
    ParamType::Float,
    Default::Note("far_clip"),
    Range::Any,
    "has no effect: a pinhole camera is in focus everywhere",
)
.ignored();
const NORI_WIDTH: Param = Param::new(
    "width",
    ParamType::Integer,
    Default::Integer(1280),
    EDGE,
    "image width on a Nori camera (which then takes no film)",
);
const NORI_HEIGHT: Param = Param::new(
    "height",
    ParamType::Integer,
    Default::Integer(720),
    EDGE,
    "image height on a Nori camera",
);

/// `perspective`.
pub const PERSPECTIVE: SensorPlugin = Plugin {
    name: "perspective",
    aliases: &[],
    doc: "A pinhole camera.",
    params: &[
        TO_WORLD,
        FOV,
        FOV_AXIS,
        FOCAL_LENGTH,
        NEAR_CLIP,
        FAR_CLIP,
        FOCUS_DISTANCE,
        NORI_WIDTH,
        NORI_HEIGHT,
    ],
    nested: "an optional `<film>`, `<rfilter>` and `<sampler>`",
    build: build_perspective,
};

fn build_perspective(obj: &Object, warnings: &mut Vec<String>) -> Result<SensorParts> {
    let to_world = TO_WORLD.read_transform(obj)?;
    // Nori's camera carries width/height and clips at 1e-4; Mitsuba's sensor clips at 0.01.
    let nori = obj.has("width") || obj.has("height");
    let near = NEAR_CLIP.read_f32_or(obj, if nori { 1e-4 } else { 0.01 })?;
    let far = FAR_CLIP.read_f32_where(obj, 10000.0, |v| v > near as f64)?;
    FOCUS_DISTANCE.read_f32_opt(obj)?;
    let (fov, axis) = match FOV.read_f32_opt(obj)? {
        Some(fov) => {
            let axis = match FOV_AXIS.read_choice(obj)? {
                "y" => FovAxis::Y,
                "diagonal" => FovAxis::Diagonal,
                "smaller" => FovAxis::Smaller,
                "larger" => FovAxis::Larger,
                _ => FovAxis::X,
            };
            (fov, axis)
        }
        None => {
            let s = FOCAL_LENGTH.read_string(obj)?;
            let f: f64 = s.trim_end_matches("mm").trim().parse().ok().filter(|f: &f64| *f > 0.0 && f.is_finite()).ok_or_else(|| {
                at_prop(obj, "focal_length", format!("\"focal_length\" must be a positive length like \"50mm\", found \"{s}\""))
            })?;
            let diag = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            (
                (2.0 * (diag / (2.0 * f)).atan()).to_degrees() as f32,
                FovAxis::Diagonal,
            )
        }
    };
    let mut filter = Filter::Gaussian(GaussianFilter::new(0.5));
    let (mut width, mut height) = (768, 576);
    // Nori: width/height (and the filter) on the camera itself.
    if obj.has("width") || obj.has("height") {
        width = edge(obj, &NORI_WIDTH)?;
        height = edge(obj, &NORI_HEIGHT)?;
    }
    let (mut spp, mut seed, mut sampler) = (None, None, None);
    for c in &obj.children {
        match c.obj.kind {
            Kind::Film => {
                c.mark_used();
                let film = &c.obj;
                let plugin = plugin::find(FILMS, "film", film)?;
                (width, height) = (plugin.build)(film)?;
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
    let camera = Perspective::new(to_world, width, height, fov, axis, near, far);
    Ok(SensorParts {
        camera,
        filter,
        spp,
        seed,
        sampler,
    })
}

#[cfg(test)]
mod tests {
    use crate::plugin::check::check_family;
    use crate::xml::Kind;

    #[test]
    fn declarations_match_what_the_builders_read() {
        check_family(
            super::SENSORS,
            Kind::Sensor,
            |obj| super::build_sensor(obj, &mut Vec::new()),
            // fov_axis is read with fov; focal_length only without it.
            |_| "<float name=\"fov\" value=\"45\"/>".to_string(),
            // A camera that carries width/height is Nori's: its near_clip default differs.
            &[
                ("perspective", "width"),
                ("perspective", "height"),
                ("perspective", "focal_length"),
            ],
        );
        check_family(
            super::FILMS,
            Kind::Film,
            |obj| (super::FILMS[0].build)(obj),
            |_| String::new(),
            &[],
        );
    }
}

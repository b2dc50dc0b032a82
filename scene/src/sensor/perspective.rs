//! `<sensor type="perspective">` (a pinhole) and `<sensor type="thinlens">` (the same
//! projection through a thin lens), with Mitsuba 3's field of view and principal point
//! parameters. Mitsuba 3.9.1's `thinlens` does not read the principal point offsets (its
//! parser refuses them as unreferenced); Tessera gives them the same meaning as on
//! `perspective`.
use super::film::{edge, read_film, EDGE};
use super::fov::{read_fov, FOCAL_LENGTH, FOV, FOV_AXIS};
use super::{parts, read_clips, read_shutter, SensorParts, SensorPlugin};
use super::{FAR_CLIP, NEAR_CLIP, SHUTTER_CLOSE, SHUTTER_OPEN, TO_WORLD};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use glam::Vec2;
use tessera_core::camera::{Camera, Perspective, Projection, ThinLens};

const PRINCIPAL_X: Param = Param::float(
    "principal_point_offset_x",
    0.0,
    Range::Any,
    "shift of the principal point, in film widths: pixel x sees what pixel x + offset * width \
     saw without it",
);
const PRINCIPAL_Y: Param = Param::float(
    "principal_point_offset_y",
    0.0,
    Range::Any,
    "shift of the principal point, in film heights: pixel y sees what pixel y + offset * height \
     saw without it",
);
const PINHOLE_FOCUS: Param = Param::new(
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
const APERTURE_RADIUS: Param = Param::new(
    "aperture_radius",
    ParamType::Float,
    Default::Required,
    Range::NonNegative,
    "radius of the lens's aperture, in scene units (0: a pinhole)",
);
const LENS_FOCUS: Param = Param::new(
    "focus_distance",
    ParamType::Float,
    Default::Note("far_clip"),
    Range::Note("positive"),
    "distance along the view axis to the plane in focus",
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
        PRINCIPAL_X,
        PRINCIPAL_Y,
        PINHOLE_FOCUS,
        SHUTTER_OPEN,
        SHUTTER_CLOSE,
        NORI_WIDTH,
        NORI_HEIGHT,
    ],
    nested: "an optional `<film>`, `<rfilter>` and `<sampler>`",
    build: build_perspective,
};

/// `thinlens`.
pub const THINLENS: SensorPlugin = Plugin {
    name: "thinlens",
    aliases: &[],
    doc: "A perspective camera with a thin lens: depth of field.",
    params: &[
        TO_WORLD,
        APERTURE_RADIUS,
        LENS_FOCUS,
        FOV,
        FOV_AXIS,
        FOCAL_LENGTH,
        NEAR_CLIP,
        FAR_CLIP,
        PRINCIPAL_X,
        PRINCIPAL_Y,
        SHUTTER_OPEN,
        SHUTTER_CLOSE,
    ],
    nested: "an optional `<film>`, `<rfilter>` and `<sampler>`",
    build: build_thinlens,
};

fn build_perspective(obj: &Object, warnings: &mut Vec<String>) -> Result<SensorParts> {
    let to_world = TO_WORLD.read_transform(obj)?;
    // Nori's camera carries width/height and clips at 1e-4; Mitsuba's sensor clips at 0.01.
    let nori = obj.has("width") || obj.has("height");
    let (near, far) = read_clips(obj, if nori { 1e-4 } else { 0.01 })?;
    PINHOLE_FOCUS.read_f32_opt(obj)?;
    read_shutter(obj)?;
    let (fov, axis) = read_fov(obj)?;
    let offset = read_principal_point(obj)?;
    let size = if nori {
        (edge(obj, &NORI_WIDTH)?, edge(obj, &NORI_HEIGHT)?)
    } else {
        (768, 576)
    };
    let film = read_film(obj, size, warnings)?;
    Ok(parts(film, |width, height| {
        let p = Perspective::new(width, height, fov, axis, near, far)
            .with_principal_point_offset(offset);
        Camera {
            to_world,
            width,
            height,
            projection: Projection::Perspective(p),
            crop: None,
        }
    }))
}

fn build_thinlens(obj: &Object, warnings: &mut Vec<String>) -> Result<SensorParts> {
    let to_world = TO_WORLD.read_transform(obj)?;
    let aperture_radius = APERTURE_RADIUS.read_f32(obj)?;
    let (near, far) = read_clips(obj, 0.01)?;
    let focus_distance = LENS_FOCUS.read_f32_where(obj, far as f64, |v| v > 0.0)?;
    read_shutter(obj)?;
    let (fov, axis) = read_fov(obj)?;
    let offset = read_principal_point(obj)?;
    let film = read_film(obj, (768, 576), warnings)?;
    Ok(parts(film, |width, height| {
        let pinhole = Perspective::new(width, height, fov, axis, near, far)
            .with_principal_point_offset(offset);
        // Mitsuba 3 replaces a zero radius by a tiny one: a pinhole, which draws no lens sample.
        let projection = if aperture_radius == 0.0 {
            Projection::Perspective(pinhole)
        } else {
            Projection::ThinLens(ThinLens {
                pinhole,
                aperture_radius,
                focus_distance,
            })
        };
        Camera {
            to_world,
            width,
            height,
            projection,
            crop: None,
        }
    }))
}

/// The principal point offset, in film widths and heights.
fn read_principal_point(obj: &Object) -> Result<Vec2> {
    Ok(Vec2::new(
        PRINCIPAL_X.read_f32(obj)?,
        PRINCIPAL_Y.read_f32(obj)?,
    ))
}

//! `<sensor type="orthographic">`: parallel rays, with Mitsuba 3's meaning of `to_world` (its
//! scale sets the size of the view, which spans `[-1, 1]` along local x before it).
use super::film::read_film;
use super::{parts, read_clips, read_shutter, SensorParts, SensorPlugin};
use super::{FAR_CLIP, NEAR_CLIP, SHUTTER_CLOSE, SHUTTER_OPEN};
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::camera::{Camera, Orthographic, Projection};

const TO_WORLD: Param = Param::transform(
    "to_world",
    "camera to world; the camera looks down its local +z, with +y up, and sees the rectangle \
     [-1, 1] x [-1/aspect, 1/aspect] of its local xy plane (scale it to see more)",
);
const FOCUS_DISTANCE: Param = Param::new(
    "focus_distance",
    ParamType::Float,
    Default::Note("far_clip"),
    Range::Any,
    "has no effect: an orthographic camera is in focus everywhere",
)
.ignored();

/// `orthographic`.
pub const ORTHOGRAPHIC: SensorPlugin = Plugin {
    name: "orthographic",
    aliases: &[],
    doc: "Parallel projection along the camera's local +z.",
    params: &[
        TO_WORLD,
        NEAR_CLIP,
        FAR_CLIP,
        FOCUS_DISTANCE,
        SHUTTER_OPEN,
        SHUTTER_CLOSE,
    ],
    nested: "an optional `<film>`, `<rfilter>` and `<sampler>`",
    build: build_orthographic,
};

fn build_orthographic(obj: &Object, warnings: &mut Vec<String>) -> Result<SensorParts> {
    let to_world = TO_WORLD.read_transform(obj)?;
    let (near, far) = read_clips(obj, 0.01)?;
    FOCUS_DISTANCE.read_f32_opt(obj)?;
    read_shutter(obj)?;
    let film = read_film(obj, (768, 576), warnings)?;
    Ok(parts(film, |width, height| Camera {
        to_world,
        width,
        height,
        projection: Projection::Orthographic(Orthographic { near, far }),
        crop: None,
    }))
}
